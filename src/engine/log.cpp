// Rank-0 logging to screen and file.
#include "narrows/engine/log.hpp"

#include <iostream>

namespace narrows::engine {

Log::Log(bool is_root, const std::string &file) : root_(is_root) {
  if (root_ && !file.empty())
    file_.open(file, std::ios::out | std::ios::trunc);
}

void Log::line(const std::string &text) {
  if (!root_)
    return;
  std::cout << text << '\n' << std::flush;
  if (file_.is_open())
    file_ << text << '\n' << std::flush;
}

} // namespace narrows::engine
