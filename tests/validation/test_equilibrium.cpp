// Equilibrium of the periodic MPCD fluid: Maxwell-Boltzmann velocities and kT.
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace narrows;

namespace {

scene::Scene box_scene(int dim, scene::Collision rule) {
  scene::Scene s;
  s.run.dimensions = dim;
  s.run.seed = 2024;
  s.domain.size =
      dim == 2 ? std::array<double, 3>{64.0, 64.0, 0.0} : std::array<double, 3>{16.0, 16.0, 16.0};
  s.fluid.collision = rule;
  s.fluid.density = 10.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 130.0;
  s.fluid.kT = 1.0;
  return s;
}

// Kolmogorov-Smirnov distance between the sample and the standard normal CDF.
double ks_distance(std::vector<double> z) {
  std::sort(z.begin(), z.end());
  const double n = static_cast<double>(z.size());
  double d = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double F = 0.5 * std::erfc(-z[i] / std::sqrt(2.0));
    d = std::max({d, std::abs(F - i / n), std::abs((i + 1) / n - F)});
  }
  return d;
}

} // namespace

// The run starts far from equilibrium: every velocity component is +-1 (a two-point
// distribution with kT = 1 and zero total momentum), which fails the KS test below by a factor
// ~80 (sqrt(N) D ~ 0.34 sqrt(4e4)), so a collision that does nothing (or only permutes
// velocities) cannot pass. The collisions make it Gaussian within ~10 steps; sample after 200
// steps from well-separated snapshots. KS: with N independent samples,
// P(sqrt(N) D > 1.95) = 0.001.
// Velocities of particles in one snapshot are nearly independent (correlations O(1/N)).
// Temperature: the average of 20 snapshots of N ~ 4e4 particles has a relative standard error
// ~ sqrt(2/(d N 20)) ~ 1.1e-3 (2D); the test allows 0.5 %.
class Equilibrium : public ::testing::TestWithParam<std::tuple<int, scene::Collision>> {};

TEST_P(Equilibrium, MaxwellBoltzmannAndTemperature) {
  const auto [dim, rule] = GetParam();
  mpcd::MpcdSimulation sim(box_scene(dim, rule), MPI_COMM_SELF);
  auto &f = sim.fluid();
  ASSERT_EQ(f.size() % 8, 0u); // bit k of i sums to zero over the ids for k < 3
  for (int k = 0; k < dim; ++k)
    for (std::size_t i = 0; i < f.size(); ++i)
      f.v[k][i] = (i >> k) & 1 ? 1.0 : -1.0;
  for (int k = 0; k < dim; ++k) { // the start really is far from Maxwell-Boltzmann
    const double n = static_cast<double>(f.size());
    ASSERT_GT(std::sqrt(n) * ks_distance(f.v[k]), 20.0) << "axis " << k;
  }
  for (int i = 0; i < 200; ++i)
    sim.advance();
  double kT_sum = 0.0;
  const int snapshots = 20;
  for (int s = 0; s < snapshots; ++s) {
    for (int i = 0; i < 25; ++i)
      sim.advance();
    kT_sum += analysis::temperature(sim.fluid(), MPI_COMM_SELF);
    if (s % 10 == 0)
      for (int k = 0; k < dim; ++k) {
        const double D = ks_distance(sim.fluid().v[k]);
        const double n = static_cast<double>(sim.fluid().size());
        EXPECT_LT(std::sqrt(n) * D, 1.95) << "axis " << k << " snapshot " << s;
      }
  }
  const double kT = kT_sum / snapshots;
  EXPECT_NEAR(kT, 1.0, 0.005) << "measured kT " << kT;
  std::printf("[ measured ] dim %d rule %s: kT = %.5f\n", dim, scene::to_string(rule), kT);
}

INSTANTIATE_TEST_SUITE_P(Rules, Equilibrium,
                         ::testing::Values(std::make_tuple(2, scene::Collision::srd),
                                           std::make_tuple(3, scene::Collision::srd),
                                           std::make_tuple(2, scene::Collision::at),
                                           std::make_tuple(3, scene::Collision::at),
                                           std::make_tuple(2, scene::Collision::at_a),
                                           std::make_tuple(3, scene::Collision::at_a),
                                           std::make_tuple(2, scene::Collision::random_permute),
                                           std::make_tuple(2, scene::Collision::random_maxwell)));
