// 1D d'Humieres lattice gas: the enumerated collision table conserves mass and momentum and is
// symmetric, collide/propagate conserve them on a lattice, draws are pure functions of
// (seed, step, site), and the initial ensembles hold what they promise.
#include "narrows/engines/lgca/dhumieres_1d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace {

using namespace narrows::lgca;
using dhumieres::mass;
using dhumieres::momentum;

TEST(Dhumieres1d, CollisionTableConservesMassAndMomentumForAll32States) {
  const auto t = dhumieres::collision_table();
  for (int s = 0; s < 32; ++s) {
    const auto s8 = static_cast<std::uint8_t>(s);
    ASSERT_GE(t.count[s], 1);
    EXPECT_EQ(t.members[s][0], s8);
    for (int k = 0; k < t.count[s]; ++k) {
      const auto o = t.members[s][k];
      EXPECT_LT(o, 32);
      EXPECT_EQ(mass(o), mass(s8)) << "state " << s << " -> " << int(o);
      EXPECT_EQ(momentum(o), momentum(s8)) << "state " << s << " -> " << int(o);
    }
  }
}

TEST(Dhumieres1d, CollisionTableHoldsWholeClassesOfAtMostTwo) {
  const auto t = dhumieres::collision_table();
  std::map<std::pair<int, int>, std::set<int>> classes;
  for (int s = 0; s < 32; ++s)
    classes[{mass(std::uint8_t(s)), momentum(std::uint8_t(s))}].insert(s);
  int pairs = 0;
  for (int s = 0; s < 32; ++s) {
    const auto &cls = classes[{mass(std::uint8_t(s)), momentum(std::uint8_t(s))}];
    std::set<int> got;
    for (int k = 0; k < t.count[s]; ++k)
      got.insert(t.members[s][k]);
    EXPECT_EQ(got, cls) << "state " << s;
    EXPECT_LE(cls.size(), 2u);
    pairs += cls.size() == 2;
  }
  EXPECT_EQ(pairs, 12); // six classes of two, listed in dhumieres_1d.hpp
}

// Every site, every step: no collision changes a site's mass or momentum, under either rule,
// and the ring keeps N and P.
TEST(Dhumieres1d, CollideAndPropagateConserveMassAndMomentumOnTheRing) {
  const auto t = dhumieres::collision_table();
  for (auto rule : {dhumieres::Rule::swap, dhumieres::Rule::random}) {
    std::vector<std::uint8_t> state(96), next(96);
    for (std::size_t r = 0; r < state.size(); ++r)
      state[r] = static_cast<std::uint8_t>((r * 7) % 32); // every state, in several places
    const auto n0 = dhumieres::total_mass(state);
    const auto p0 = dhumieres::total_momentum(state);
    for (std::uint64_t step = 1; step <= 50; ++step) {
      auto before = state;
      dhumieres::collide(state, t, rule, 9, step);
      for (std::size_t r = 0; r < state.size(); ++r) {
        ASSERT_EQ(mass(state[r]), mass(before[r]));
        ASSERT_EQ(momentum(state[r]), momentum(before[r]));
        if (rule == dhumieres::Rule::swap && t.count[before[r]] == 2)
          ASSERT_NE(state[r], before[r]); // swap always collides
      }
      dhumieres::propagate(state, next);
      std::swap(state, next);
      ASSERT_EQ(dhumieres::total_mass(state), n0);
      ASSERT_EQ(dhumieres::total_momentum(state), p0);
    }
  }
}

TEST(Dhumieres1d, PropagationMovesEachLinkByItsVelocity) {
  const std::int64_t L = 7;
  for (int i = 0; i < dhumieres::links; ++i) {
    std::vector<std::uint8_t> in(L, 0), out(L);
    in[1] = static_cast<std::uint8_t>(1u << i);
    dhumieres::propagate(in, out);
    const std::int64_t to = ((1 + dhumieres::velocity[i]) % L + L) % L;
    for (std::int64_t r = 0; r < L; ++r)
      EXPECT_EQ(out[r], r == to ? in[1] : 0) << "link " << i << " site " << r;
  }
}

TEST(Dhumieres1d, RandomRuleDrawsArePureFunctionsOfSeedStepSite) {
  const auto t = dhumieres::collision_table();
  const auto rule = dhumieres::Rule::random;
  std::vector<std::uint8_t> a(200), b;
  for (std::size_t r = 0; r < a.size(); ++r)
    a[r] = static_cast<std::uint8_t>((r * 13) % 32);
  b = a;
  auto c = a;
  dhumieres::collide(a, t, rule, 5, 17);
  dhumieres::collide(b, t, rule, 5, 17);
  dhumieres::collide(c, t, rule, 5, 18);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Dhumieres1d, RandomRuleCollidesWithProbabilityOneHalf) {
  const auto t = dhumieres::collision_table();
  const std::uint8_t s = 0b00011; // +1 -1 <-> +2 -2
  ASSERT_EQ(t.count[s], 2);
  const int n = 60000;
  std::vector<std::uint8_t> state(n, s);
  dhumieres::collide(state, t, dhumieres::Rule::random, 3, 1);
  int moved = 0;
  for (auto o : state) {
    ASSERT_TRUE(o == s || o == 0b01100);
    moved += o != s;
  }
  EXPECT_NEAR(moved / double(n), 0.5, 5.0 * std::sqrt(0.25 / n));
}

TEST(Dhumieres1d, InitialEnsembles) {
  const std::int64_t L = 500;
  const double d = 0.7;
  const auto ind = dhumieres::initial_state(L, d, dhumieres::Ensemble::independent, 1);
  const double n_ind = static_cast<double>(dhumieres::total_mass(ind));
  EXPECT_NEAR(n_ind, 1750.0, 5.0 * std::sqrt(2500 * d * (1 - d)));
  const auto fix = dhumieres::initial_state(L, d, dhumieres::Ensemble::fixed_number, 2);
  EXPECT_EQ(dhumieres::total_mass(fix), 1750);
  for (std::uint64_t seed = 3; seed < 6; ++seed) {
    const auto zero = dhumieres::initial_state(L, d, dhumieres::Ensemble::zero_momentum, seed);
    EXPECT_EQ(dhumieres::total_mass(zero), 1750);
    EXPECT_EQ(dhumieres::total_momentum(zero), 0);
  }
}

} // namespace
