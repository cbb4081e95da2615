// The held colloid's time averages (lattice/colloid_correlations.hpp) on a synthetic velocity
// with known correlations: an AR(1) process u(t) = phi u(t-1) + noise about a constant drift V,
// the situation of a held colloid whose fluid + colloid momentum (hence centre-of-mass
// velocity V) is conserved but not zero. Z(t) = phi^t and, per component,
// msd(t) = s2 [t (1 + phi) / (1 - phi) - 2 phi (1 - phi^t) / (1 - phi)^2].
#include "narrows/engines/lgca/colloid_correlations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace narrows::lgca;

namespace {

constexpr double phi = 0.9, s2 = 1e-4; // s2 = <u_x^2>

double msd_per_component(double t) {
  return s2 *
         (t * (1 + phi) / (1 - phi) - 2 * phi * (1 - std::pow(phi, t)) / ((1 - phi) * (1 - phi)));
}

ColloidCorrelations feed(std::array<double, 2> drift, std::array<double, 2> reference) {
  const std::int64_t steps = 400000;
  ColloidCorrelations c(50, 200, 10, steps, reference);
  std::mt19937_64 gen(5);
  std::normal_distribution<double> noise(0.0, std::sqrt(s2 * (1 - phi * phi)));
  double ux = 0.0, uy = 0.0;
  for (std::int64_t t = 0; t < steps; ++t) {
    ux = phi * ux + noise(gen);
    uy = phi * uy + noise(gen);
    c.add({drift[0] + ux, drift[1] + uy});
  }
  return c;
}

} // namespace

// With the conserved drift as reference the averages are those of the fluctuation: Z(t) = phi^t
// and D(t) = msd / (4 t) without the ballistic V^2 t / 4. A drift of 3 sqrt(s2) (a seed-11 run
// of the 128 x 128 scene had |V| ~ 0.26 sqrt(<U^2>)) taken as reference 0 is what the driver did
// before: a plateau V^2 / <U^2> in Z and D(t) growing like t. That case must fail the same checks.
TEST(ColloidCorrelations, AveragesAreOfTheFluctuationAboutTheReference) {
  const std::array<double, 2> drift{0.03, -0.01};
  const auto good = feed(drift, drift);
  const auto z = good.vacf(), d = good.diffusion();
  EXPECT_NEAR(good.mean_square_velocity(), 2 * s2, 0.05 * 2 * s2);
  for (int t : {1, 5, 10, 20, 40})
    EXPECT_NEAR(z.value[t], std::pow(phi, t), 4 * z.error[t] + 1e-3) << "lag " << t;
  for (std::size_t k = 1; k < d.lags.size(); ++k) {
    const double want = 2 * msd_per_component(d.lags[k]) / (4 * d.lags[k]);
    EXPECT_NEAR(d.value[k], want, 4 * d.error[k] + 0.01 * want) << "lag " << d.lags[k];
  }
  // the reference 0: the same checks fail by far
  const auto bad = feed(drift, {0.0, 0.0});
  EXPECT_GT(bad.vacf().value[40] - std::pow(phi, 40), 0.5);
  const auto db = bad.diffusion();
  EXPECT_GT(db.value.back(), 2.0 * d.value.back());
}

// The eq 22 analogue: vacf(p) adds p to every lag, diffusion(p) adds p <U^2> t / 4; the block
// means carry the same normalisation and average to the value.
TEST(ColloidCorrelations, PlateauAndBlocks) {
  const auto c = feed({0.0, 0.0}, {0.0, 0.0});
  const double p = 0.02;
  const auto z = c.vacf(), zp = c.vacf(p), d = c.diffusion(), dp = c.diffusion(p);
  ASSERT_EQ(zp.blocks.size(), static_cast<std::size_t>(c.blocks()) * z.lags.size());
  for (std::size_t k = 0; k < z.lags.size(); ++k) {
    EXPECT_NEAR(zp.value[k], z.value[k] + p, 1e-12);
    double mean = 0.0;
    for (int b = 0; b < c.blocks(); ++b)
      mean += zp.blocks[b * z.lags.size() + k] / c.blocks();
    EXPECT_NEAR(mean, zp.value[k], 1e-3); // block 0 has fewer origins at the longest lags
  }
  for (std::size_t k = 0; k < d.lags.size(); ++k)
    EXPECT_NEAR(dp.value[k], d.value[k] + p * c.mean_square_velocity() * d.lags[k] / 4, 1e-12);
}

// A checkpoint's state: stopping after 37 013 of 100 000 steps (not a multiple of any lag or
// block), restoring into a fresh object (built with the remaining step count and another
// reference, as a restarted run builds it) and feeding the rest gives bitwise the averages of
// the uninterrupted run; a state of other lags is refused without change.
TEST(ColloidCorrelations, StateRestoresBitwise) {
  const std::int64_t steps = 100000, cut = 37013;
  std::mt19937_64 gen(9);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<std::array<double, 2>> u(steps);
  double ux = 0.0, uy = 0.0;
  for (auto &v : u) {
    ux = phi * ux + noise(gen);
    uy = phi * uy + noise(gen);
    v = {0.003 + ux, -0.001 + uy};
  }
  ColloidCorrelations straight(50, 200, 10, steps, {0.003, -0.001});
  ColloidCorrelations first(50, 200, 10, steps, {0.003, -0.001});
  for (std::int64_t t = 0; t < steps; ++t) {
    straight.add(u[t]);
    if (t < cut)
      first.add(u[t]);
  }
  const auto saved = first.state();
  ColloidCorrelations wrong(60, 200, 10, steps - cut);
  EXPECT_FALSE(wrong.restore(saved));
  ColloidCorrelations second(50, 200, 10, steps - cut, {0.5, 0.5});
  ASSERT_TRUE(second.restore(saved));
  for (std::int64_t t = cut; t < steps; ++t)
    second.add(u[t]);
  const auto a = straight.vacf(0.01), b = second.vacf(0.01);
  const auto da = straight.diffusion(0.01), db = second.diffusion(0.01);
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.blocks, b.blocks);
  EXPECT_EQ(da.value, db.value);
  EXPECT_EQ(da.error, db.error);
  EXPECT_EQ(straight.mean_square_velocity(), second.mean_square_velocity());
  EXPECT_GT(a.error[5], 0.0); // ten blocks filled: a real comparison
  // without the state the second half alone differs
  ColloidCorrelations alone(50, 200, 10, steps - cut, {0.003, -0.001});
  for (std::int64_t t = cut; t < steps; ++t)
    alone.add(u[t]);
  EXPECT_NE(alone.vacf(0.01).value, a.value);
}
