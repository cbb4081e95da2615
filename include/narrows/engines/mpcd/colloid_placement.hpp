// The scene's colloids at the start of a run: radii and masses drawn from the scene, initial
// positions as a row along x (lattice), a list from the scene, random without overlap or a
// packing; and the fluid particles left beside them. The engine turns the scene into colloids
// here; the geometry and the fluid's exclusion test are colloids/placement.hpp.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/packing.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/scene/scene.hpp"

#include <cstdint>
#include <functional>

namespace narrows::mpcd {

// The radius of colloid `id`: spec.radius, or with spec.radius_sd > 0 a Gaussian deviate of
// mean radius and standard deviation radius_sd truncated at +-3 radius_sd (deviates beyond are
// drawn again), keyed by (seed, id) alone, so every rank draws the same radii without a message.
double colloid_radius(const scene::Colloids &spec, std::uint64_t seed, std::uint64_t id);

// Radius and mass of every colloid of the scene (ids 0..count-1): colloid_radius, and
// spec.mass_of (the fluid's mass density times the own volume unless colloids.mass is set).
void set_radii_and_masses(colloids::Colloids &c, const scene::Colloids &spec, double density,
                          std::uint64_t seed);

// All colloids of the scene, at rest, ids 0..count-1, the same on every rank, with radii and
// masses from set_radii_and_masses.
// lattice: evenly spaced along x at the centre of the cross-section;
// random: uniform, no pair closer than its 48-24 cut-off 2^(1/24) (r_a + r_b), and with walls
// no closer to a wall than the largest wall cut-off (draws keyed by (seed, attempt, index));
// input_error if 10^5 attempts cannot place a colloid;
// list (and file): the given positions, input_error naming both entries if two cores overlap
// (centres closer than r_a + r_b);
// packing: grown from random points with frictionless springs (colloids/packing.hpp, the same on
// every rank), what it reached into `report` if given; input_error if the overlaps cannot be
// removed; `poll` is called during the packing (colloids::PackingParams::poll).
colloids::Colloids place_colloids(const scene::Colloids &spec, const mpcd::Box &box, double density,
                                  std::uint64_t seed, colloids::PackingReport *report = nullptr,
                                  const std::function<void()> &poll = {});

// Fluid particles the scene has with colloids: round(n (V_box - sum_a V_a)) (Tabatabaei (2008)
// §3.4.1: N_f = n (L_x L_y - N_c pi r_c^2) for equal radii); `seed` draws the radii.
std::uint64_t fluid_count_with_colloids(const scene::Colloids &spec, const mpcd::Box &box,
                                        double density, std::uint64_t seed);

} // namespace narrows::mpcd
