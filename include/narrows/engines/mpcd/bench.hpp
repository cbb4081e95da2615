// `narrows bench`: throughput of the hot kernels on this machine, next to a memory-bandwidth
// bound measured here (STREAM triad). Prints figures; never asserts a time.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace narrows::mpcd {

struct BenchOptions {
  bool json = false;
  double particles = 1.0e6;       // per case
  int steps = 100;                // timed steps per case (after a warm-up)
  std::vector<std::string> cases; // MPCD cases to run by name (empty: all)
};

void run_bench(const BenchOptions &options, std::ostream &out);

} // namespace narrows::mpcd
