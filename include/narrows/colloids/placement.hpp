// Initial colloid positions: a row along x (lattice), a list from the scene, or random without
// overlap; and the test "inside a colloid" used to keep fluid particles out of them.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/packing.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// The radius of colloid `id`: spec.radius, or with spec.radius_sd > 0 a Gaussian deviate of
// mean radius and standard deviation radius_sd truncated at +-3 radius_sd (deviates beyond are
// drawn again), keyed by (seed, id) alone, so every rank draws the same radii without a message.
double colloid_radius(const scene::Colloids &spec, std::uint64_t seed, std::uint64_t id);

// Radius and mass of every colloid of the scene (ids 0..count-1): colloid_radius, and
// spec.mass_of (the fluid's mass density times the own volume unless colloids.mass is set).
void set_radii_and_masses(Colloids &c, const scene::Colloids &spec, double density,
                          std::uint64_t seed);

// All colloids of the scene, at rest, ids 0..count-1, the same on every rank, with radii and
// masses from set_radii_and_masses.
// lattice: evenly spaced along x at the centre of the cross-section;
// random: uniform, no pair closer than its 48-24 cut-off 2^(1/24) (r_a + r_b), and with walls
// no closer to a wall than the largest wall cut-off (draws keyed by (seed, attempt, index));
// input_error if 10^5 attempts cannot place a colloid;
// list (and file): the given positions, input_error naming both entries if two cores overlap
// (centres closer than r_a + r_b);
// packing: grown from random points with frictionless springs (packing.hpp, the same on every
// rank), what it reached into `report` if given; input_error if the overlaps cannot be removed.
Colloids place_colloids(const scene::Colloids &spec, const mpcd::Box &box, double density,
                        std::uint64_t seed, PackingReport *report = nullptr);

// Fluid particles the scene has with colloids: round(n (V_box - sum_a V_a)) (Tabatabaei (2008)
// §3.4.1: N_f = n (L_x L_y - N_c pi r_c^2) for equal radii); `seed` draws the radii.
std::uint64_t fluid_count_with_colloids(const scene::Colloids &spec, const mpcd::Box &box,
                                        double density, std::uint64_t seed);

// True if p lies within distance r_a of the centre of a colloid a (minimum image along periodic
// axes).
bool inside_any(const Colloids &c, const mpcd::Box &box, const std::array<double, 3> &p);

// The colloids that overlap each collision cell of the box (cells of size 1), for keeping the
// initial fluid out of them in O(colloids per cell) per test.
class ColloidCover {
public:
  ColloidCover(const Colloids &c, const mpcd::Box &box);
  // The same as inside_any(c, box, p).
  bool inside(const std::array<double, 3> &p) const;

private:
  const Colloids &c_;
  mpcd::Box box_;
  std::vector<std::uint32_t> offset_, list_; // colloids of cell g: list_[offset_[g], offset_[g+1])
};

} // namespace narrows::colloids
