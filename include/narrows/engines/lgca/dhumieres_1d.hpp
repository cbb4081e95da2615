// The 1D lattice gas of d'Humieres, Lallemand and Qian (van der Hoef & Frenkel ref [12]):
// velocities 0, +-1, +-2 on a periodic ring, at most one particle per velocity per site,
// collisions that conserve mass and momentum at each site. One byte per site; bit i is the link
// of velocity[i].
#pragma once

#include "narrows/engines/lgca/moment_propagation.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace narrows::lgca::dhumieres {

inline constexpr int links = 5;
inline constexpr std::array<int, links> velocity = {1, -1, 2, -2, 0}; // bit 4: rest particle

int mass(std::uint8_t s);     // number of particles at a site
int momentum(std::uint8_t s); // sum of their velocities

// Collision table built by enumerating all 32 states and grouping them by (mass, momentum).
// Enumeration gives classes of one or two members only: {+1 -1, +2 -2}, {0 +1, -1 +2},
// {0 -1, +1 -2}, {0 +1 -1, 0 +2 -2}, {0 -1 +2, +1 +2 -2}, {0 +1 -2, -1 +2 -2}.
struct CollisionTable {
  std::array<std::array<std::uint8_t, 32>, 32> members{}; // members[s][0..count[s]-1], s first
  std::array<std::uint8_t, 32> count{};
};
CollisionTable collision_table();

// The outcome rule. swap: a uniformly random *other* member of the class - the most mixing rule
// the conservation laws allow; since every class has at most two members it is deterministic
// here (every collidable state always collides), which gives the shortest mean free time.
// random: a uniformly random member including the state itself (collide with probability 1/2
// in a class of two), a stochastic variant. Both are symmetric, T(s -> s') = T(s' -> s), so the
// uniform product (Fermi-Dirac) measure is stationary (semi-detailed balance).
enum class Rule { swap, random };

// Collides every site in place; a draw (rule random, or swap in a class of three or more) is a
// pure function of (seed, step, site).
void collide(std::span<std::uint8_t> state, const CollisionTable &table, Rule rule,
             std::uint64_t seed, std::uint64_t step);

// Streams every particle by its velocity around the ring: out[r + c_i] gets bit i of in[r].
void propagate(std::span<const std::uint8_t> in, std::span<std::uint8_t> out);

// The ensembles an initial state is drawn from (all stationary under the dynamics).
enum class Ensemble {
  independent,   // every link occupied with probability d independently (grand canonical)
  fixed_number,  // exactly N = round(L b d) particles, uniformly placed on the L b links
  zero_momentum, // fixed_number and total momentum exactly 0 (the MD {N, P = 0} ensemble),
                 // by rejection: an exact sample of the product measure restricted to (N, 0)
};
std::vector<std::uint8_t> initial_state(std::int64_t L, double d, Ensemble ensemble,
                                        std::uint64_t seed);

std::int64_t total_mass(std::span<const std::uint8_t> state);
std::int64_t total_momentum(std::span<const std::uint8_t> state);

// The link velocities and ring neighbours for moment propagation.
Links link_velocities();
NeighbourTable neighbours(std::int64_t L);

} // namespace narrows::lgca::dhumieres
