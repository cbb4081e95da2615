// DirectWriter: staged, block-aligned O_DIRECT writes of one byte range of a file.
#include "narrows/io/direct_writer.hpp"

#include "narrows/core/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace narrows::io {

namespace {

constexpr std::uint64_t block = 4096;                  // O_DIRECT alignment of offsets and lengths
constexpr std::size_t capacity = std::size_t{8} << 20; // staging buffer, a multiple of block

std::uint64_t round_up(std::uint64_t x) { return (x + block - 1) / block * block; }

} // namespace

void DirectWriter::Free::operator()(char *p) const { std::free(p); }

DirectWriter::DirectWriter(const std::string &path, std::uint64_t start, std::uint64_t end)
    : path_(path), next_(start), end_(end) {
  fd_ = ::open(path.c_str(), O_WRONLY);
  if (fd_ < 0)
    throw Error(ExitCode::other, path + ": cannot open for writing (" + std::strerror(errno) + ")");
  direct_fd_ = ::open(path.c_str(), O_WRONLY | O_DIRECT);
  void *p = nullptr;
  if (posix_memalign(&p, block, capacity) != 0)
    throw Error(ExitCode::other, path + ": cannot allocate the write buffer");
  buffer_.reset(static_cast<char *>(p));
}

DirectWriter::~DirectWriter() {
  if (direct_fd_ >= 0)
    ::close(direct_fd_);
  if (fd_ >= 0)
    ::close(fd_);
}

void DirectWriter::write_at(int fd, const char *data, std::size_t size, std::uint64_t offset) {
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, data, size, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0 && fd == direct_fd_ && errno == EINVAL) {
      // The file system takes no O_DIRECT after all: ordinary writes from here on.
      ::close(direct_fd_);
      direct_fd_ = -1;
      fd = fd_;
      continue;
    }
    if (n <= 0)
      throw Error(ExitCode::other, path_ + ": write failed (" +
                                       std::string(n < 0 ? std::strerror(errno) : "no progress") +
                                       ")");
    data += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
}

// Writes the staged bytes up to the last block boundary of the file; keeps the rest at the
// front of the (block-aligned) buffer.
void DirectWriter::flush_aligned() {
  char *buf = buffer_.get();
  auto drop = [&](std::size_t n) {
    std::memmove(buf, buf + n, staged_ - n);
    staged_ -= n;
    next_ += n;
  };
  // An unaligned start goes through the page cache up to the first boundary (once).
  const std::size_t head =
      static_cast<std::size_t>(std::min<std::uint64_t>(round_up(next_) - next_, staged_));
  if (head > 0) {
    write_at(fd_, buf, head, next_);
    drop(head);
  }
  const std::size_t aligned = staged_ / block * block;
  if (aligned > 0) {
    write_at(direct_fd_ >= 0 ? direct_fd_ : fd_, buf, aligned, next_);
    drop(aligned);
  }
}

void DirectWriter::append(const void *data, std::size_t size) {
  const char *src = static_cast<const char *>(data);
  while (size > 0) {
    const std::size_t n = std::min(size, capacity - staged_);
    std::memcpy(buffer_.get() + staged_, src, n);
    staged_ += n;
    src += n;
    size -= n;
    if (staged_ == capacity)
      flush_aligned();
  }
}

void DirectWriter::finish() {
  flush_aligned();
  if (next_ + staged_ != end_)
    throw Error(ExitCode::other, path_ + ": " + std::to_string(next_ + staged_) +
                                     " bytes written where the range ends at " +
                                     std::to_string(end_));
  if (staged_ > 0) // the unaligned tail, through the page cache
    write_at(fd_, buffer_.get(), staged_, next_);
  next_ += staged_;
  staged_ = 0;
  if (::fdatasync(fd_) != 0)
    throw Error(ExitCode::other, path_ + ": fdatasync failed (" + std::strerror(errno) + ")");
}

} // namespace narrows::io
