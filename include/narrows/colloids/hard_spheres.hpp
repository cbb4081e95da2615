// Event-driven rough hard spheres (Kanehl (thesis) §4.2.2, eq 4.19-4.33): colloids move
// ballistically and collide instantaneously, earliest collision first, from a priority queue of
// predicted events. At contact the relative velocity of the touching surface points, U (eq 4.26),
// is reversed whole: its normal part (elastic) and its tangential part (no slip, fig 4.5). The
// impulse that does so (eq 4.27-4.29) conserves momentum, angular momentum and kinetic energy
// (translational plus rotational). Walls at y = 0 and y = L_y (with box.walls_y) are rough
// hard walls at rest: infinite mass, the same rule.
//
// Disks (2D, moment of inertia M R^2 / 2, spin omega[2]) and spheres (3D, 2 M R^2 / 5). Periodic
// axes use the minimum image; a colloid must not travel more than a few radii in one call.
//
// The no-slip coupling (no_slip.hpp) moves colloids with it when `[colloids] contacts = "hard"`.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Moment of inertia of colloid a: M R^2 / 2 (disk) or 2 M R^2 / 5 (sphere).
double moment_of_inertia(const Colloids &c, std::size_t a);

// The rough collision of touching colloids a and b (eq 4.26-4.33): updates their velocities
// and spins. `d` = x_a - x_b at contact (minimum image), |d| = r_a + r_b.
void collide_rough(Colloids &c, std::size_t a, std::size_t b, const double d[3]);

// The rough collision of colloid a with a wall at rest whose normal (into the channel) is
// n = (0, +-1, 0): `side` +1 for the wall at y = 0, -1 for the wall at y = L_y.
void collide_rough_wall(Colloids &c, std::size_t a, int side);

struct HardSphereStats {
  std::uint64_t pair_collisions = 0, wall_collisions = 0;
};

// Moves every colloid of c ballistically over time dt, resolving each collision exactly in
// time order (no overlap is ever created). Positions along periodic axes end wrapped into the
// box. Returns the counts of events. Each colloid keeps its own time, so its path depends only
// on the collisions it takes part in, and ties go by id: a colloid's path is the same whichever
// other colloids are present, as long as those it meets (directly or through others) are.
// `trusted` (optional, one flag per row): a collision between a trusted and an untrusted row
// makes both untrusted (a ghost near the edge of a rank's region may have missed a partner).
// Only the pairs in neighbouring cells of the start positions are predicted; `every_pair`
// predicts all (the same events: for the tests).
HardSphereStats advance_hard_spheres(Colloids &c, const mpcd::Box &box, double dt,
                                     std::vector<std::uint8_t> *trusted = nullptr,
                                     bool every_pair = false);

// Kinetic energy of translation and rotation of all colloids of c.
double kinetic_energy(const Colloids &c);

} // namespace narrows::colloids
