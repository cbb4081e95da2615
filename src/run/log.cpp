// Rank-0 logging to screen and file; the progress and Loop time lines.
#include "narrows/run/log.hpp"

#include <cstdio>
#include <iostream>

namespace narrows::run {

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

std::string format_duration(double seconds) {
  char buf[32];
  const long s = static_cast<long>(seconds + 0.5);
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

std::string progress_line(std::int64_t step, std::int64_t first, std::int64_t end, double seconds,
                          double per_step, const char *rate_unit, const char *what) {
  const double rate = static_cast<double>(step - first) / seconds;
  char head[120], mid[80] = "";
  std::snprintf(head, sizeof head, "%s %lld / %lld (%.1f %%)", what, static_cast<long long>(step),
                static_cast<long long>(end),
                100.0 * static_cast<double>(step) / static_cast<double>(end));
  if (rate_unit != nullptr)
    std::snprintf(mid, sizeof mid, ", %.3g %s", rate * per_step, rate_unit);
  return std::string(head) + mid + ", ETA " +
         format_duration(static_cast<double>(end - step) / rate);
}

std::string loop_time_line(double seconds, int ranks, std::uint64_t count, const char *count_unit,
                           const std::string &with, double work, const char *rate_unit) {
  char buf[300];
  std::snprintf(buf, sizeof buf, "Loop time of %.4g s on %d ranks for %llu %s with %s (%.4g %s/s)",
                seconds, ranks, static_cast<unsigned long long>(count), count_unit, with.c_str(),
                seconds > 0 ? work / seconds : 0.0, rate_unit);
  return buf;
}

} // namespace narrows::run
