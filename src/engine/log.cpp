// Rank-0 logging to screen and file.
#include "narrows/engine/log.hpp"

#include "narrows/core/error.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <system_error>

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

void make_output_dir(const std::string &dir, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::error_code ec;
  if (rank == 0)
    std::filesystem::create_directories(dir, ec);
  int failed = ec ? 1 : 0;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
    throw input_error(dir + ": cannot create output directory" +
                      (rank == 0 ? " (" + ec.message() + ")" : std::string()));
}

RunOutput open_run_output(const std::string &dir, std::int64_t continued_from,
                          const std::string &scene_file, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  make_output_dir(dir, comm);
  char suffix[24] = "";
  if (continued_from >= 0)
    std::snprintf(suffix, sizeof suffix, "-%010lld", static_cast<long long>(continued_from));
  RunOutput out{suffix, Log(rank == 0, dir + "/log" + suffix + ".txt")};
  out.log.line("narrows " NARROWS_VERSION " run " + scene_file + " on " + std::to_string(ranks) +
               " rank(s), output in " + dir);
  return out;
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
                          double per_step, const char *rate_unit) {
  const double rate = static_cast<double>(step - first) / seconds;
  char buf[200];
  std::snprintf(buf, sizeof buf, "step %lld / %lld (%.1f %%), %.3g %s, ETA %s",
                static_cast<long long>(step), static_cast<long long>(end),
                100.0 * static_cast<double>(step) / static_cast<double>(end), rate * per_step,
                rate_unit, format_duration(static_cast<double>(end - step) / rate).c_str());
  return buf;
}

} // namespace narrows::engine
