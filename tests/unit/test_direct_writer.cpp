// DirectWriter: byte ranges with unaligned starts and ends, smaller than a block, larger than
// the staging buffer, and adjacent ranges sharing a block all land exactly where they belong.
#include "narrows/io/direct_writer.hpp"

#include "narrows/core/error.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

namespace {

using narrows::io::DirectWriter;

TEST(DirectWriter, RangesLandExactly) {
  const auto path = std::filesystem::temp_directory_path() / "narrows-direct-writer-test.bin";
  // Range boundaries: unaligned, inside one block, a range over 8 MiB, adjacent ranges.
  const std::vector<std::uint64_t> cuts{0, 13, 4000, 4100, 4101, 12289, 9000000, 9000001, 9000777};
  const std::uint64_t size = cuts.back() + 1000;
  std::vector<unsigned char> expected(size, 0);
  std::mt19937_64 gen(5);
  for (auto &b : expected)
    b = static_cast<unsigned char>(gen());
  {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(std::vector<char>(size, 0).data(), static_cast<std::streamsize>(size));
  }
  // Ranges written in a scrambled order, each appended in pieces of varying size.
  const std::vector<std::size_t> order{3, 0, 7, 5, 1, 6, 2, 4};
  for (const std::size_t j : order) {
    DirectWriter w(path.string(), cuts[j], cuts[j + 1]);
    std::uint64_t at = cuts[j];
    std::size_t piece = 1;
    while (at < cuts[j + 1]) {
      const std::size_t n = std::min<std::uint64_t>(piece, cuts[j + 1] - at);
      w.append(&expected[at], n);
      at += n;
      piece = piece * 3 + 7;
    }
    w.finish();
  }
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> got((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
  ASSERT_EQ(got.size(), size);
  for (std::uint64_t i = 0; i < size; ++i) {
    const unsigned char want = i < cuts.back() ? expected[i] : 0;
    ASSERT_EQ(got[i], want) << "byte " << i;
  }
  std::filesystem::remove(path);
}

TEST(DirectWriter, ShortRangeIsAnError) {
  const auto path = std::filesystem::temp_directory_path() / "narrows-direct-writer-short.bin";
  std::ofstream(path, std::ios::binary | std::ios::trunc) << std::string(100, 'x');
  DirectWriter w(path.string(), 10, 50);
  const char data[20] = {};
  w.append(data, sizeof data);
  EXPECT_THROW(w.finish(), narrows::Error);
  std::filesystem::remove(path);
}

} // namespace
