// `narrows bench --dem N`: the spring-contact (DEM) kernel alone, without fluid, on a dense
// bidisperse packing of N disks in a walled channel, in contact updates per second on one core;
// optionally the same packing and velocities as a LAMMPS data file, so that LAMMPS' pair
// gran/hooke/history can be timed on it (tools/dem_vs_lammps.sh).
#pragma once

#include <ostream>
#include <string>

namespace narrows::colloids {

struct DemBenchOptions {
  double disks = 1.8e5;    // disks in the channel (rounded up to whole tiles)
  int steps = 20;          // timed MPCD steps of `substeps` spring sub-steps each
  std::string lammps_data; // if not empty: write the packing here (LAMMPS data file)
  bool json = false;
};

// The packing: Kanehl (thesis) Table 6.1's mixture (a = 2.1 and 2.94, number ratio 1 : 1) at area
// fraction 0.8 between walls 50 apart, grown by colloids/packing.hpp on a tile of 1000 disks,
// periodic along x, and the tile repeated along x. Velocities and spins thermal at kT = 1,
// disks density-matched to rho = 25; k_n = k_t = 2500, mu = 1 (colloid-colloid and wall),
// 10 sub-steps of dt = 0.02: Table 6.1. Prints the contacts per sub-step, contact updates/s and
// disk sub-steps/s.
void run_dem_bench(const DemBenchOptions &options, std::ostream &out);

} // namespace narrows::colloids
