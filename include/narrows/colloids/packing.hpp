// Dense packings of colloids as in Kanehl (thesis) §6.1: the colloids start as points placed at
// random in the box, grow in steps to their radii, and after each step the linear spring contacts
// (springs.hpp, the same kernel and pair search as the run) push the overlaps apart, without
// fluid. The fluid is filled in afterwards by the usual initialisation (it skips every point
// inside a colloid, placement.hpp ColloidCover).
//
// The overlaps are removed by minimising the elastic energy of frictionless springs (k_n = 1,
// k_t = 0, mu = 0: only the positions of the minimum matter, not its stiffness) with FIRE
// (Bitzek et al., PRL 97, 170201 (2006)): damped dynamics of unit masses whose velocity is
// turned towards the force and zeroed when it runs uphill. Every number is computed in a fixed
// order on one process, so the packing is a function of the seed alone: every rank computes the
// same packing.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <cstdint>
#include <functional>
#include <string>

namespace narrows::colloids {

struct PackingParams {
  // Accept the packing when the deepest overlap (pairs and walls) is below this fraction of the
  // smallest radius.
  double tolerance = 0.005;
  // The radii grow by scale factors s from `start` to 1; each step raises the area (volume)
  // fraction by at most `growth` (times the target fraction), less near the end.
  double start = 0.5;
  double growth = 0.01;
  // A growth stage whose overlaps stay after `patience` FIRE iterations is jammed: it is
  // shaken (the radii go back `back` growth steps, the centres move at random by up to `jolt`
  // of their radius) and grown again.
  std::int64_t patience = 20000;
  double back = 20.0;
  double jolt = 0.3;
  // FIRE iterations and shakes allowed in all (input_error beyond: the target cannot be
  // packed).
  std::int64_t max_iterations = 2000000;
  std::int64_t max_shakes = 20;
  // Called every few FIRE iterations (the same ones on every rank: the packing is the same
  // everywhere); it may throw to end the packing, e.g. on a stop signal (a large packing takes
  // minutes, before the run loop asks for signals).
  std::function<void()> poll;
};

struct PackingReport {
  double fraction = 0.0;    // area (volume) fraction of the colloids in the box
  double max_overlap = 0.0; // deepest overlap / smallest radius
  std::int64_t stages = 0, iterations = 0, shakes = 0;
  double seconds = 0.0;
};

// The work of packing n colloids, estimated before it is made, in colloid-steps (each FIRE
// relaxation step computes the spring forces on every colloid): n (1e4 + n), the relaxation
// steps growing with the number of colloids (longer chains of contacts relax more slowly, and
// more of the ~170 growth stages jam and are shaken). Calibrated on the dense channel of Kanehl
// (thesis) Table 6.1 (phi = 0.75, 2w = 50; docs/scenes.md, "packing"): 1098 to 17558 disks took
// 9280 to 31540 steps, about 1e7 colloid-steps a second; looser packings take fewer.
double packing_work(std::size_t n);

// Places the colloids of c (radius set, positions overwritten, velocities zeroed) as a packing
// in `box` with draws keyed by (seed, id). With walls the centres start at least their radius
// from the walls. input_error naming `key` if the overlaps cannot be brought below the
// tolerance within max_iterations. At the end the rows are numbered along x
// (number_along_x).
PackingReport pack_colloids(Colloids &c, const mpcd::Box &box, std::uint64_t seed,
                            const std::string &key, const PackingParams &params = {});

// Rows of the same radius and mass (interchangeable) exchange their state (position,
// velocity, spin, orientation) so that within each such group the row order is the order in
// x: colloids near in the channel are then near in memory, which the loops over neighbours
// (contacts, bounce-back, ghosts) read faster. (LAMMPS sorts its atoms in space likewise.)
void number_along_x(Colloids &c);

// The deepest overlap r_a + r_b - |x_a - x_b| of two colloids or of a colloid and a wall
// (0 if none), from the same cell-list pair search as the contacts.
double max_overlap(const Colloids &c, const mpcd::Box &box);

} // namespace narrows::colloids
