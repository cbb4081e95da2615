// Checksums of checkpoint datasets: a 64-bit hash per row, seeded with the row's global index,
// summed modulo 2^64 over the rows. The sum does not depend on which rank hashed which rows nor
// in which order (MPI_Allreduce with MPI_SUM on uint64 wraps the same way), so a checkpoint
// written on P ranks verifies when read on Q. Each word enters the row hash through a bijective
// mixer, so any change of one word (a flipped bit) changes that row's hash and hence the sum:
// a single damaged word is detected with certainty, several with probability 1 - 2^-64.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace narrows::io {

// The splitmix64 finaliser: a bijection of 64-bit words with full avalanche.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Hash of row `row` (global index) holding `n` 64-bit words: one multiply by an odd constant
// per word (a bijection of the word for the hash so far, so any change of one word changes the
// row's hash) and a final mix (so that changes in several rows do not cancel in the sum).
// Cheap enough that a checkpoint's throughput stays near the disk's.
inline std::uint64_t row_hash(std::uint64_t row, const std::uint64_t *words, std::size_t n) {
  std::uint64_t h = (row + 1) * 0x9e3779b97f4a7c15ULL;
  for (std::size_t k = 0; k < n; ++k)
    h = (h ^ words[k]) * 0xd6e8feb86659fd93ULL;
  h ^= h >> 32;
  h *= 0xd6e8feb86659fd93ULL;
  return h ^ (h >> 32);
}

// Sum of the row hashes of rows [first, first + rows) stored row-major, `width` words each.
inline std::uint64_t rows_hash(std::uint64_t first, const void *data, std::size_t rows,
                               std::size_t width) {
  const auto *w = static_cast<const std::uint64_t *>(data);
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < rows; ++i)
    sum += row_hash(first + i, w + i * width, width);
  return sum;
}

// The same sum for rows stored as W separate component arrays (structure of arrays): row i is
// (cols[0][i], ..., cols[W-1][i]) as the checkpoint stores it.
template <int W>
std::uint64_t columns_hash(std::uint64_t first, const double *const *cols, std::size_t rows) {
  const double *c[W];
  for (int k = 0; k < W; ++k)
    c[k] = cols[k];
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    std::uint64_t w[W];
    for (int k = 0; k < W; ++k)
      std::memcpy(&w[k], c[k] + i, 8);
    sum += row_hash(first + i, w, W);
  }
  return sum;
}

// Hash of a small object of any size (a string, a scalar, a short array) as one row of words,
// the last one zero-padded; the byte count is mixed in so padding cannot hide a length change.
inline std::uint64_t bytes_hash(const void *data, std::size_t size) {
  const auto *b = static_cast<const unsigned char *>(data);
  std::uint64_t h = mix64(size ^ 0x6a09e667f3bcc909ULL);
  for (std::size_t at = 0; at < size; at += 8) {
    std::uint64_t w = 0;
    std::memcpy(&w, b + at, size - at < 8 ? size - at : 8);
    h = mix64(h ^ w);
  }
  return h;
}

} // namespace narrows::io
