// Log lines from rank 0 only: to the screen and to DIR/log.txt.
#pragma once

#include <fstream>
#include <string>

namespace narrows::engine {

class Log {
public:
  Log(bool is_root, const std::string &file); // file empty: screen only
  void line(const std::string &text);
  void warn(const std::string &text) { line("warning: " + text); }

private:
  bool root_;
  std::ofstream file_;
};

} // namespace narrows::engine
