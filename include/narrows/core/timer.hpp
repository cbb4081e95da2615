// Wall-clock timing for the loop summary and benchmarks.
#pragma once

#include <chrono>

namespace narrows {

class Stopwatch {
public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

private:
  std::chrono::steady_clock::time_point start_;
};

// Adds the seconds from its construction to its destruction (on every way out) to `total`.
class ScopedSeconds {
public:
  explicit ScopedSeconds(double &total) : total_(total) {}
  ScopedSeconds(const ScopedSeconds &) = delete;
  ScopedSeconds &operator=(const ScopedSeconds &) = delete;
  ~ScopedSeconds() { total_ += clock_.seconds(); }

private:
  double &total_;
  Stopwatch clock_;
};

} // namespace narrows
