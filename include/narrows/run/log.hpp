// Log lines from rank 0 only (screen and DIR/log.txt), and the texts of the lines every run
// prints: progress with ETA and the final "Loop time" summary.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>

namespace narrows::run {

class Log {
public:
  Log() = default;                            // screen only, rank 0
  Log(bool is_root, const std::string &file); // file empty: screen only
  void line(const std::string &text);
  void warn(const std::string &text) { line("warning: " + text); }

private:
  bool root_ = false;
  std::ofstream file_;
};

// "42s", "3m05s", "2h10m": for ETAs in progress lines.
std::string format_duration(double seconds);

// "<what> S / END (P %), R <rate_unit>, ETA T": progress of a run that started at `first`
// `seconds` ago; `per_step` is what one step updates (particles, sites). Without a rate_unit
// the rate is left out ("replica 8 / 16 (50.0 %), ETA 3s").
std::string progress_line(std::int64_t step, std::int64_t first, std::int64_t end, double seconds,
                          double per_step, const char *rate_unit, const char *what = "step");

// "Loop time of T s on P ranks for C <count_unit> with <with> (R <rate_unit>/s)", R = work /
// seconds.
std::string loop_time_line(double seconds, int ranks, std::uint64_t count, const char *count_unit,
                           const std::string &with, double work, const char *rate_unit);

} // namespace narrows::run
