// Initial colloid positions: a row along x (lattice), a list from the scene, or random without
// overlap; and the test "inside a colloid" used to keep fluid particles out of them.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/mpcd/fluid.hpp"
#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>

namespace narrows::colloids {

// All colloids of the scene, at rest, ids 0..count-1, the same on every rank.
// lattice: evenly spaced along x at the centre of the cross-section;
// random: uniform, no two closer than the 48-24 cut-off 2^(1/24) 2 r_c, and with walls no
// closer to a wall than the wall potential's cut-off (draws keyed by (seed, attempt, index));
// input_error if 10^5 attempts cannot place a colloid.
Colloids place_colloids(const scene::Colloids &spec, const mpcd::Box &box, double density,
                        std::uint64_t seed);

// Fluid particles the scene has with colloids: round(n (V_box - N_c V_colloid)) (seed 000
// §3.4.1: N_f = n (L_x L_y - N_c pi r_c^2)).
std::uint64_t fluid_count_with_colloids(const scene::Colloids &spec, const mpcd::Box &box,
                                        double density);

// True if p lies within distance r_c of a colloid centre (minimum image along periodic axes).
bool inside_any(const Colloids &c, const mpcd::Box &box, const std::array<double, 3> &p);

} // namespace narrows::colloids
