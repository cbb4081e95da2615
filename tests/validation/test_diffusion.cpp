// SRD self-diffusion against D = (kT dt/2)[d n/(f(n)(1 - cos alpha)) - 1] at lambda >= 0.5.
#include "diffusion.hpp"

#include "narrows/engines/mpcd/transport_theory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numbers>

using namespace narrows;

namespace {

struct Case {
  const char *name;
  int dim;
  double dt, angle_deg, L;
};

class SelfDiffusion : public ::testing::TestWithParam<Case> {};

} // namespace

// The MSD slope between lags 10 and 40 steps (well past the exponential decay of the velocity
// correlation, which takes ~1/(1 - <cos>) ~ 2 collisions here) over 10 independent windows of
// ~1e5 particles: statistical error ~0.1 %, far inside the 3 % asked. In 2D the t^-1 velocity
// tail adds a slowly growing (logarithmic) part on top of the molecular-chaos value; at these
// lags it is +2-3 %, which the 3 % tolerance still covers - it is measured, not fitted away.
TEST_P(SelfDiffusion, MatchesKineticTheory) {
  const Case c = GetParam();
  scene::Scene s;
  s.run.dimensions = c.dim;
  s.run.seed = 11;
  s.domain.size = {c.L, c.L, c.dim == 3 ? c.L : 0.0};
  s.fluid.density = 10.0;
  s.fluid.dt = c.dt;
  s.fluid.angle_deg = c.angle_deg;
  const auto r = validation::measure_diffusion(s, 50, 10, 10, 40);
  const double theory =
      mpcd::srd_self_diffusion(c.dim, 10.0, c.dt, c.angle_deg * std::numbers::pi / 180.0, 1.0);
  const double dev = r.D / theory - 1.0;
  std::printf("[ measured ] %s: D = %.5f +- %.5f, theory %.5f, deviation %+.2f %%\n", c.name, r.D,
              r.D_error, theory, 100.0 * dev);
  EXPECT_LT(r.D_error / r.D, 0.01);
  EXPECT_LT(std::abs(dev), 0.03);
}

INSTANTIATE_TEST_SUITE_P(Srd, SelfDiffusion,
                         ::testing::Values(Case{"srd3d_a90_dt1", 3, 1.0, 90.0, 30.0},
                                           Case{"srd3d_a130_dt0.5", 3, 0.5, 130.0, 30.0},
                                           Case{"srd2d_a90_dt1", 2, 1.0, 90.0, 100.0}),
                         [](const auto &info) {
                           std::string n = info.param.name;
                           std::replace(n.begin(), n.end(), '.', '_');
                           return n;
                         });
