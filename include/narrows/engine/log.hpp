// Log lines from rank 0 only: to the screen and to DIR/log.txt.
#pragma once

#include <mpi.h>

#include <cstdint>
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

// Rank 0 creates the output directory; every rank learns whether that worked, so all stop
// together with one bad-input error (exit 2) naming the directory.
void make_output_dir(const std::string &dir, MPI_Comm comm);

// The output of one run: DIR made (make_output_dir), the suffix its files carry ("" for a
// fresh run, "-<step as 10 digits>" for a continuation from `continued_from` >= 0, so that it
// keeps what earlier runs wrote: log-0000001000.txt, observables-0000001000.h5), and
// DIR/log<suffix>.txt opened with the run's first line (version, scene, ranks, directory).
struct RunOutput {
  std::string suffix;
  Log log;
};
RunOutput open_run_output(const std::string &dir, std::int64_t continued_from,
                          const std::string &scene_file, MPI_Comm comm);

// "42s", "3m05s", "2h10m": for ETAs in progress lines.
std::string format_duration(double seconds);

// "step S / END (P %), R <rate_unit>, ETA T": progress of a run that started at step `first`
// `seconds` ago; `per_step` is what one step updates (particles, sites).
std::string progress_line(std::int64_t step, std::int64_t first, std::int64_t end, double seconds,
                          double per_step, const char *rate_unit);

} // namespace narrows::engine
