// Writes one contiguous byte range of an existing file, mostly with O_DIRECT: the bytes are
// staged in a block-aligned buffer; the unaligned head and tail of the range go through the
// page cache, every aligned block in between straight to the disk, so a large checkpoint is
// not copied twice in memory nor written back after the fact. Falls back to ordinary writes
// where the file system refuses O_DIRECT. Several ranks may write disjoint ranges of one file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace narrows::io {

class DirectWriter {
public:
  // Opens `path` (which must exist) to write bytes [start, end). Throws narrows::Error naming
  // the file if it cannot be opened.
  DirectWriter(const std::string &path, std::uint64_t start, std::uint64_t end);
  ~DirectWriter();
  DirectWriter(const DirectWriter &) = delete;
  DirectWriter &operator=(const DirectWriter &) = delete;

  // Appends the next `size` bytes of the range.
  void append(const void *data, std::size_t size);
  // Writes what is staged, checks that the whole range was given, and syncs the file's data.
  void finish();
  bool direct() const { return direct_fd_ >= 0; }

private:
  void write_at(int fd, const char *data, std::size_t size, std::uint64_t offset);
  void flush_aligned();

  std::string path_;
  std::uint64_t next_, end_; // file offset of the first staged byte; end of the range
  int fd_ = -1, direct_fd_ = -1;
  struct Free {
    void operator()(char *p) const;
  };
  std::unique_ptr<char, Free> buffer_;
  std::size_t staged_ = 0;
};

} // namespace narrows::io
