// The 1D d'Humieres-Lallemand-Qian lattice gas (see lattice/dhumieres_1d.hpp).
#include "narrows/engines/lgca/dhumieres_1d.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"

#include <bit>
#include <cmath>
#include <numeric>
#include <string>

namespace narrows::lgca::dhumieres {

int mass(std::uint8_t s) { return std::popcount(static_cast<unsigned>(s)); }

int momentum(std::uint8_t s) {
  int p = 0;
  for (int i = 0; i < links; ++i)
    if ((s >> i) & 1u)
      p += velocity[i];
  return p;
}

CollisionTable collision_table() {
  CollisionTable t;
  for (int s = 0; s < 32; ++s) {
    const auto s8 = static_cast<std::uint8_t>(s);
    t.members[s][t.count[s]++] = s8;
    for (int o = 0; o < 32; ++o) {
      const auto o8 = static_cast<std::uint8_t>(o);
      if (o != s && mass(o8) == mass(s8) && momentum(o8) == momentum(s8))
        t.members[s][t.count[s]++] = o8;
    }
  }
  return t;
}

void collide(std::span<std::uint8_t> state, const CollisionTable &table, Rule rule,
             std::uint64_t seed, std::uint64_t step) {
  for (std::size_t r = 0; r < state.size(); ++r) {
    const std::uint8_t s = state[r];
    const unsigned n = table.count[s];
    if (n == 1)
      continue;
    // swap picks among members 1..n-1 (the others), random among 0..n-1
    const unsigned first = rule == Rule::swap ? 1u : 0u;
    const unsigned choices = n - first;
    if (choices == 1) {
      state[r] = table.members[s][first];
      continue;
    }
    const auto w = rng::draw(seed, rng::Purpose::dhumieres_collision, step, r)[0];
    const auto k = static_cast<unsigned>((static_cast<std::uint64_t>(w) * choices) >> 32);
    state[r] = table.members[s][first + k];
  }
}

void propagate(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  const auto L = static_cast<std::int64_t>(in.size());
  for (auto &o : out)
    o = 0;
  for (std::int64_t r = 0; r < L; ++r) {
    const std::uint8_t s = in[r];
    for (int i = 0; i < links; ++i) {    // branch-free: the bits are random
      std::int64_t to = r + velocity[i]; // |velocity| <= 2 < L: one wrap at most
      to += to < 0 ? L : (to >= L ? -L : 0);
      out[to] = static_cast<std::uint8_t>(out[to] | (s & (1u << i)));
    }
  }
}

std::int64_t total_mass(std::span<const std::uint8_t> state) {
  std::int64_t n = 0;
  for (auto s : state)
    n += mass(s);
  return n;
}

std::int64_t total_momentum(std::span<const std::uint8_t> state) {
  std::int64_t p = 0;
  for (auto s : state)
    p += momentum(s);
  return p;
}

namespace {

// Exactly n particles on uniformly chosen links (partial Fisher-Yates over the L b links).
std::vector<std::uint8_t> place(std::int64_t L, std::int64_t n, std::uint64_t seed,
                                std::uint64_t round) {
  std::vector<std::int64_t> idx(static_cast<std::size_t>(L * links));
  std::iota(idx.begin(), idx.end(), 0);
  const auto m = static_cast<std::int64_t>(idx.size());
  for (std::int64_t k = 0; k < n; ++k) {
    const auto w = rng::draw(seed, rng::Purpose::lgca_initial, round, k);
    const auto j = k + static_cast<std::int64_t>(rng::uniform53(w[0], w[1]) * (m - k));
    std::swap(idx[k], idx[j]);
  }
  std::vector<std::uint8_t> state(static_cast<std::size_t>(L), 0);
  for (std::int64_t k = 0; k < n; ++k)
    state[idx[k] / links] =
        static_cast<std::uint8_t>(state[idx[k] / links] | (1u << (idx[k] % links)));
  return state;
}

} // namespace

std::vector<std::uint8_t> initial_state(std::int64_t L, double d, Ensemble ensemble,
                                        std::uint64_t seed) {
  if (L < 3)
    throw input_error("lattice.size = [" + std::to_string(L) +
                      "] not allowed for dhumieres-1d; need L >= 3");
  if (!(d > 0.0 && d < 1.0))
    throw input_error("lattice.density = " + std::to_string(d) + " not allowed; need 0 < d < 1");
  if (ensemble == Ensemble::independent) {
    std::vector<std::uint8_t> state(static_cast<std::size_t>(L), 0);
    const auto threshold = static_cast<std::uint64_t>(d * 4294967296.0);
    for (std::int64_t r = 0; r < L; ++r) {
      const auto w0 = rng::draw(seed, rng::Purpose::lgca_initial, 0, r);
      const auto w1 = rng::draw(seed, rng::Purpose::lgca_initial, 1, r);
      std::uint8_t s = 0;
      for (int i = 0; i < links; ++i)
        if ((i < 4 ? w0[i] : w1[i - 4]) < threshold)
          s = static_cast<std::uint8_t>(s | (1u << i));
      state[r] = s;
    }
    return state;
  }
  const auto n = static_cast<std::int64_t>(std::llround(static_cast<double>(L) * links * d));
  if (ensemble == Ensemble::fixed_number)
    return place(L, n, seed, 0);
  // Rejection keeps each accepted state exactly as likely as under the uniform placement;
  // the acceptance is P(P = 0) ~ 1 / sqrt(2 pi N (1 - d) <c^2>), about 1/160 at N = 7000.
  constexpr std::uint64_t max_rounds = 1000000;
  for (std::uint64_t round = 0; round < max_rounds; ++round) {
    auto state = place(L, n, seed, round);
    if (total_momentum(state) == 0)
      return state;
  }
  throw input_error("dhumieres-1d: no zero-momentum state found in " + std::to_string(max_rounds) +
                    " draws");
}

Links link_velocities() {
  Links l;
  for (int v : velocity)
    l.cx.push_back(v);
  return l;
}

NeighbourTable neighbours(std::int64_t L) { return ring_neighbours(L, velocity); }

} // namespace narrows::lgca::dhumieres
