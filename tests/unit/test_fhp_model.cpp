// FHP collision tables generated from the rules: conservation, semi-detailed balance, the
// rules of each model, and the Boltzmann viscosity of the table against PHYSICS.md.
#include "narrows/engines/lgca/fhp_model.hpp"

#include <gtest/gtest.h>

#include <array>

using namespace narrows::lgca;

namespace {

const std::array<FhpModel, 4> all_models = {FhpModel::fhp_i, FhpModel::fhp_ii, FhpModel::fhp_iii,
                                            FhpModel::fhp_saturated};

} // namespace

TEST(FhpModel, CollisionsConserveMassAndMomentum) {
  for (const auto m : all_models) {
    const auto t = make_collision_table(m);
    for (int s = 0; s < (1 << links(m)); ++s)
      for (int c = 0; c < 2; ++c) {
        const auto s2 = t.out[c][s];
        EXPECT_LT(s2, 1 << links(m)) << to_string(m) << " state " << s;
        EXPECT_EQ(mass(s2), mass(static_cast<std::uint8_t>(s))) << to_string(m) << " " << s;
        EXPECT_EQ(momentum_units(s2), momentum_units(static_cast<std::uint8_t>(s)))
            << to_string(m) << " " << s;
      }
  }
}

// Semi-detailed balance (the H theorem of the Boltzmann equation): every state is reached
// with total probability 1, i.e. twice over the two chiralities.
TEST(FhpModel, SemiDetailedBalance) {
  for (const auto m : all_models) {
    const auto t = make_collision_table(m);
    std::array<int, 128> in{};
    for (int s = 0; s < (1 << links(m)); ++s)
      for (int c = 0; c < 2; ++c)
        ++in[t.out[c][s]];
    for (int s = 0; s < (1 << links(m)); ++s)
      EXPECT_EQ(in[s], 2) << to_string(m) << " state " << s;
  }
}

TEST(FhpModel, FhpIRules) {
  const auto t = make_collision_table(FhpModel::fhp_i);
  // Head-on {0, 3} -> {1, 4} or {2, 5}, one per chirality.
  EXPECT_EQ(t.out[0][0x09], 0x12);
  EXPECT_EQ(t.out[1][0x09], 0x24);
  // Symmetric triples swap.
  EXPECT_EQ(t.out[0][0x15], 0x2A);
  EXPECT_EQ(t.out[1][0x2A], 0x15);
  // Head-on pair with a spectator {0, 3, 1} does not collide in FHP-I, nor two head-on pairs.
  EXPECT_EQ(t.out[0][0x0B], 0x0B);
  EXPECT_EQ(t.out[1][0x1B], 0x1B);
  int colliding = 0;
  for (int s = 0; s < 64; ++s)
    colliding += t.out[0][s] != s;
  EXPECT_EQ(colliding, 5);
}

TEST(FhpModel, FhpIIRules) {
  const auto t = make_collision_table(FhpModel::fhp_ii);
  // Rest + link 0 <-> links {1, 5}.
  EXPECT_EQ(t.out[0][0x41], 0x22);
  EXPECT_EQ(t.out[1][0x22], 0x41);
  // Head-on with a rest spectator rotates, the rest particle stays.
  EXPECT_EQ(t.out[0][0x49], 0x52);
  EXPECT_EQ(t.out[1][0x49], 0x64);
  // Triple with a rest spectator.
  EXPECT_EQ(t.out[0][0x55], 0x6A);
  // Head-on + moving spectator does not collide in FHP-II.
  EXPECT_EQ(t.out[0][0x0B], 0x0B);
}

TEST(FhpModel, SaturatedModelsChangeEveryStateThatCan) {
  for (const auto m : {FhpModel::fhp_iii, FhpModel::fhp_saturated}) {
    const auto t = make_collision_table(m);
    for (int s = 0; s < (1 << links(m)); ++s) {
      int others = 0; // states with the same mass and momentum
      for (int u = 0; u < (1 << links(m)); ++u)
        others += u != s &&
                  mass(static_cast<std::uint8_t>(u)) == mass(static_cast<std::uint8_t>(s)) &&
                  momentum_units(static_cast<std::uint8_t>(u)) ==
                      momentum_units(static_cast<std::uint8_t>(s));
      for (int c = 0; c < 2; ++c)
        EXPECT_EQ(t.out[c][s] != s, others > 0) << to_string(m) << " state " << s;
    }
  }
  // FHP-III: head-on + moving spectator goes to the other head-on + the same spectator.
  const auto t = make_collision_table(FhpModel::fhp_iii);
  EXPECT_EQ(momentum_units(t.out[0][0x0B]), momentum_units(0x0B));
  EXPECT_NE(t.out[0][0x0B], t.out[1][0x0B]);
}

// The linearised Boltzmann operator of the generated table reproduces the closed forms of
// PHYSICS.md at every density: this checks the tables against the models' definitions.
TEST(FhpModel, TableViscosityEqualsBoltzmannFormula) {
  for (const auto m : all_models)
    for (const double d : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8}) {
      const double want = boltzmann_viscosity(m, d);
      EXPECT_NEAR(table_viscosity(make_collision_table(m), d), want, 1e-12 * want)
          << to_string(m) << " d = " << d;
    }
  EXPECT_NEAR(boltzmann_viscosity(FhpModel::fhp_saturated, 0.5), 7.0 / 72.0, 1e-15);
}
