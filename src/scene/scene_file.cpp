// Reading a scene file: regular files only, one-line errors for what cannot be read.
#include "narrows/scene/parse.hpp"

#include "message_text.hpp"
#include "narrows/core/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

namespace narrows::scene {

namespace {

using detail::one_line;

std::string read_file(const std::string &path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw input_error(one_line(path + ": cannot open scene file (" + std::strerror(EISDIR) + ")"));
  // A FIFO or device would block or never end: only regular files are read.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw input_error(one_line(path + ": not a regular file (a FIFO, socket or device); allowed: "
                                      "a scene file"));
  errno = 0;
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (f == nullptr)
    throw input_error(one_line(path + ": cannot open scene file (" +
                               std::strerror(errno ? errno : ENOENT) + ")"));
  std::string text;
  char buf[65536];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
    text.append(buf, n);
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (failed)
    throw input_error(
        one_line(path + ": cannot read scene file (" + std::strerror(err ? err : EIO) + ")"));
  return text;
}

} // namespace

Scene load_scene(const std::string &path, const std::vector<std::string> &overrides) {
  return parse_scene(read_file(path), path, overrides);
}

} // namespace narrows::scene
