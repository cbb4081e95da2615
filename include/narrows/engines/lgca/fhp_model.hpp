// FHP lattice-gas models on the triangular lattice and their collision tables, generated from
// the collision rules (never typed in), plus the Boltzmann viscosities of PHYSICS.md.
//
// A site's state is one byte: bit i (i = 0..5) is the particle on link i with velocity
// c_i = (cos(pi i/3), sin(pi i/3)); bit 6 is the rest particle (7-bit models only).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace narrows::lgca {

enum class FhpModel { fhp_i, fhp_ii, fhp_iii, fhp_saturated };

const char *to_string(FhpModel m);

// Links per site: 6 (FHP-I, saturated 6-bit) or 7 (with the rest particle).
int links(FhpModel m);

inline constexpr std::uint8_t rest_bit = 0x40;

// out[chirality][state]: the post-collision state for one random bit per site and step.
// Entries of states that cannot occur (the rest bit in a 6-bit model) map to themselves.
struct CollisionTable {
  FhpModel model = FhpModel::fhp_i;
  std::array<std::array<std::uint8_t, 128>, 2> out{};
};

// The table of a model. States are grouped by mass and momentum; within a group, the states
// that take part in the model's collisions go to one another: to the rotations by +-60
// degrees (chosen by the chirality bit) when both are in the group, else to the other member
// (or one of the two others, chosen by the chirality bit). Colliding states:
//   fhp-i          head-on pairs and symmetric triples (6 bits)
//   fhp-ii         fhp-i with or without a rest-particle spectator, and rest + i <-> {i-1, i+1}
//   fhp-iii        every state of a group with more than one member (7 bits, saturated)
//   fhp-saturated  every state of a group with more than one member (6 bits)
CollisionTable make_collision_table(FhpModel m);

// Bounce-back at a solid site: every moving particle reverses (i -> i + 3), rest stays.
std::uint8_t bounce_back(std::uint8_t state);

// Mass and momentum of a state: momentum in units (c_x: halves, c_y: sqrt(3)/2) as integers.
int mass(std::uint8_t state);
std::array<int, 2> momentum_units(std::uint8_t state);

// Relaxation rate lambda of the traceless stress mode Q_i = c_ix^2 - 1/2 under the Boltzmann
// (uncorrelated) collision operator of `table`, linearised about uniform occupation d; the
// Boltzmann kinematic viscosity is then nu = 1/(4 lambda) - 1/8 (lattice units).
double shear_relaxation_rate(const CollisionTable &table, double d);
double table_viscosity(const CollisionTable &table, double d);

// The closed forms of PHYSICS.md ("Lattice gases").
double boltzmann_viscosity(FhpModel m, double d);

} // namespace narrows::lgca
