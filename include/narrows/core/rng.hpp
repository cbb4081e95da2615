// Counter-based random numbers (Philox4x32-10 from Random123): every draw is a pure function
// of (seed, purpose, step, id), so no generator state exists to communicate or checkpoint.
#pragma once

// (It includes immintrin.h, whose AVX-512 part GCC 12 warns about: a dummy operand is left
// undefined on purpose, GCC bug 105593.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Random123/philox.h>
#pragma GCC diagnostic pop

#include <array>
#include <cmath>
#include <cstdint>

namespace narrows::rng {

// What a draw is for; part of the counter so different uses never share a stream.
enum class Purpose : std::uint32_t {
  grid_shift = 1,     // id unused: (seed, step)
  srd_rotation = 2,   // id = global cell index
  at_gaussian = 3,    // id = particle id
  random_maxwell = 4, // id = particle id
  random_permute = 5, // id = position in the permutation
  init_position = 6,  // id = particle id
  init_velocity = 7,  // id = particle id
  kmc_replica = 8,    // step = word pair, id = replica: seeds a replica's stateful generator
  wall_virtual_momentum = 10, // id = global cell index: summed velocity of virtual particles
  wall_virtual_noise = 11,    // id = global cell index: summed MPC-AT noise of virtual particles
  srd_rotation_retry = 12,    // id = global cell index ^ (attempt << 56): further axis tries
  colloid_placement = 13,     // step = attempt, id = colloid index: random placement
  mc_thermostat = 14,         // id = global cell index: Monte Carlo cell thermostat
  test = 15,
  lgca_chirality = 16,      // step = lattice step, id = row * blocks + x / 128: 128 chirality bits
  lgca_init = 17,           // step = link / 4, id = global site index: initial occupations
  lgca_force = 18,          // step = lattice step, id = row * blocks + x / 8: 8 16-bit uniforms
  lgca_colloid = 19,        // step = lattice step, id = boundary link: Ladd-Frenkel transmission
  colloid_radius = 20,      // step = attempt, id = colloid id: radius from a truncated Gaussian
  ghost_position = 21,      // id = colloid id << 40 | global cell << 8 | try: ghost particle place
  ghost_velocity = 22,      // the same id: its Maxwell-Boltzmann velocity
  dhumieres_collision = 40, // id = site: outcome of a 1D d'Humieres collision
  lgca_initial = 41,        // step = draw round (attempt), id = link or site: initial occupations
  continuum_initial = 42,   // id = grid point: random initial perturbation (jamming)
};

using Block = std::array<std::uint32_t, 4>;

// Raw Philox4x32-10 of one counter/key pair (exposed for the known-answer tests).
inline Block philox4x32_10(const Block &counter, const std::array<std::uint32_t, 2> &key) {
  r123::Philox4x32 gen;
  const r123::Philox4x32::ctr_type c = {{counter[0], counter[1], counter[2], counter[3]}};
  const r123::Philox4x32::key_type k = {{key[0], key[1]}};
  const auto r = gen(c, k);
  return {r[0], r[1], r[2], r[3]};
}

// Four independent 32-bit words for (seed, purpose, step, id). The counter holds the 64-bit
// id, the low 32 bits of the step, and purpose (8 bits) with 24 more bits of the step.
inline Block draw(std::uint64_t seed, Purpose purpose, std::uint64_t step, std::uint64_t id) {
  const Block counter = {static_cast<std::uint32_t>(id), static_cast<std::uint32_t>(id >> 32),
                         static_cast<std::uint32_t>(step),
                         (static_cast<std::uint32_t>(purpose) << 24) |
                             static_cast<std::uint32_t>((step >> 32) & 0xFFFFFFu)};
  return philox4x32_10(counter,
                       {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)});
}

// Uniform in the open interval (0, 1) from 32 bits.
inline double open01(std::uint32_t u) { return (static_cast<double>(u) + 0.5) * 0x1p-32; }

// Uniform in [0, 1) with 53-bit resolution from two words.
inline double uniform53(std::uint32_t hi, std::uint32_t lo) {
  const std::uint64_t bits = (static_cast<std::uint64_t>(hi) << 21) ^ (lo >> 11);
  return static_cast<double>(bits & ((1ull << 53) - 1)) * 0x1p-53;
}

// Four standard normal deviates by Box-Muller from one block.
inline std::array<double, 4> gaussian4(const Block &b) {
  constexpr double two_pi = 6.283185307179586;
  const double r0 = std::sqrt(-2.0 * std::log(open01(b[0])));
  const double r1 = std::sqrt(-2.0 * std::log(open01(b[2])));
  const double t0 = two_pi * open01(b[1]);
  const double t1 = two_pi * open01(b[3]);
  return {r0 * std::cos(t0), r0 * std::sin(t0), r1 * std::cos(t1), r1 * std::sin(t1)};
}

// The first two deviates of gaussian4 (the same values) at half the cost, for 2D.
inline std::array<double, 2> gaussian2(const Block &b) {
  constexpr double two_pi = 6.283185307179586;
  const double r0 = std::sqrt(-2.0 * std::log(open01(b[0])));
  const double t0 = two_pi * open01(b[1]);
  return {r0 * std::cos(t0), r0 * std::sin(t0)};
}

} // namespace narrows::rng
