// `narrows bench`: throughput of the hot kernels on this machine, next to a memory-bandwidth
// bound measured here (STREAM triad on arrays as large as each case's working set, which is
// printed beside the last-level cache size), and the coupled Table 6.1 channel (pulses-2d) with
// its no-slip coupling's share of the loop. Prints figures; never asserts a time.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace narrows::mpcd {

struct BenchOptions {
  bool json = false;
  // Per case; 0: the smallest box whose working set (fluid arrays and cell grid) is at least 4
  // times the last-level cache (and at least 1e6 particles); pulses-2d: the scene's 187150.
  double particles = 0.0;
  int steps = 100;                // timed steps per case (after a warm-up of 20)
  double angle_deg = 130.0;       // rotation angle of the SRD cases
  std::vector<std::string> cases; // MPCD cases to run by name (empty: all)
};

void run_bench(const BenchOptions &options, std::ostream &out);

} // namespace narrows::mpcd
