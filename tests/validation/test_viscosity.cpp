// Kolmogorov-flow viscosity against kinetic theory (PHYSICS.md "Viscosity theory" and
// "Measuring nu honestly"): SRD 2D/3D at lambda >= 0.5 within 3 %, MPC-AT within 5 %, MPC-AT+a
// measured and printed next to the large-n formula.
//
// How the runs are sized (all from the estimates below, no tuning to theory):
// - laminar: Re_k = u0/(k nu) < 1, below the sqrt(2) instability of long Kolmogorov boxes;
// - heating: SRD conserves energy, so kT rises by ~u0^2/2 per relaxation time 1/(k^2 nu); with
//   u0 ~ 0.06 and ~100 relaxation times the rise is ~15 %, and theory is evaluated at the
//   measured mean temperature (the flow's own kinetic energy subtracted);
// - statistics: the sin(ky) mode amplitude of N particles fluctuates by sqrt(2 kT/N); 20
//   blocks of ~5 relaxation times give a block-average error of ~1 %, which the test also
//   requires (error < tolerance/2), so a pass is not luck.
#include "kolmogorov.hpp"

#include "narrows/engines/mpcd/transport_theory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

using namespace narrows;

namespace {

struct Case {
  const char *name;
  int dim;
  scene::Collision rule;
  double n, dt, angle_deg;
  std::array<double, 3> size;
  double amplitude;
  int warmup, blocks, block_steps;
  double tolerance; // relative; 0 = report only
  // An expected deviation from theory (if hi > lo): nu / theory - 1 must lie in [lo, hi]
  // widened by 3 standard errors of the measurement.
  double expected_lo = 0.0, expected_hi = 0.0;
};

class Viscosity : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(Viscosity, KolmogorovFlowMatchesTheory) {
  const Case c = GetParam();
  const auto s =
      validation::kolmogorov_scene(c.dim, c.rule, c.n, c.dt, c.angle_deg, c.size, c.amplitude);
  const auto r = validation::measure_kolmogorov(s, c.warmup, c.blocks, c.block_steps);
  const double angle = c.angle_deg * std::numbers::pi / 180.0;
  // Theory at the measured temperature (MPC-AT rules are thermostatted to kT = 1 exactly).
  const bool thermostatted = c.rule != scene::Collision::srd;
  const auto theory = mpcd::viscosity(c.rule, c.dim, c.n, c.dt, angle, thermostatted ? 1.0 : r.kT);
  const double u0 = c.amplitude / (std::pow(2 * std::numbers::pi / c.size[1], 2) * r.nu);
  if (!theory) {
    std::printf("[ measured ] %s: nu = %.4f +- %.4f (kT %.4f, u0 %.3f); no formula for this case\n",
                c.name, r.nu, r.nu_error, r.kT, u0);
    EXPECT_LT(r.nu_error / r.nu, 0.03);
    return;
  }
  const double dev = r.nu / theory->total() - 1.0;
  std::printf("[ measured ] %s: nu = %.4f +- %.4f, theory %.4f at kT %.4f, deviation %+.2f %% "
              "(%.1f sigma), u0 %.3f\n",
              c.name, r.nu, r.nu_error, theory->total(), r.kT, 100.0 * dev,
              std::abs(r.nu - theory->total()) / r.nu_error, u0);
  if (c.expected_hi > c.expected_lo) {
    // the error bar must be small against the window, else the window cannot see a change
    const double sigma = r.nu_error / theory->total();
    EXPECT_LT(sigma, 0.5 * (c.expected_hi - c.expected_lo));
    EXPECT_GE(dev, c.expected_lo - 3.0 * sigma) << "the known deviation from theory moved";
    EXPECT_LE(dev, c.expected_hi + 3.0 * sigma) << "the known deviation from theory moved";
  } else if (c.tolerance > 0.0) {
    EXPECT_LT(r.nu_error / r.nu, 0.5 * c.tolerance) << "run too short to test the tolerance";
    EXPECT_LT(std::abs(dev), c.tolerance);
  } else {
    EXPECT_LT(r.nu_error / r.nu, 0.03);
  }
}

using scene::Collision;
INSTANTIATE_TEST_SUITE_P(
    Rules, Viscosity,
    ::testing::Values(
        // SRD 3D, lambda = 1, two angles.
        Case{"srd3d_a90_dt1",
             3,
             Collision::srd,
             10,
             1.0,
             90,
             {40, 12, 40},
             0.00756,
             80,
             20,
             40,
             0.03},
        // Seeds 7-10 give -2.7, -1.9, -1.5, -1.0 % here (the formula sits ~1.5 % high at
        // 130 deg): 40 blocks keep the error bar (~0.65 %) well inside the tolerance.
        Case{"srd3d_a130_dt1",
             3,
             Collision::srd,
             10,
             1.0,
             130,
             {40, 16, 40},
             0.0051,
             100,
             40,
             60,
             0.03},
        // SRD 2D, lambda = 0.5: the molecular-chaos formula holds within 3 % at 130 and 140 deg
        // (asserted). Measured by hand at this size: alpha = 120 -> +3.8 %, 130 -> +2.2 %,
        // 140 -> within 1 %, 150 -> -3.9 %, 90 -> +22 % (also +24 % at lambda = 1, for L_y = 12
        // and 24 alike): in 2D the formula is not within 3 % at every angle. 120 and 150 deg
        // are not run (each costs a minute, and there is no theory of their deviation); 90 deg,
        // the known failure, is an expected-deviation test below.
        Case{"srd2d_a130_dt0.5",
             2,
             Collision::srd,
             10,
             0.5,
             130,
             {416, 24, 0},
             0.00186,
             620,
             20,
             310,
             0.03},
        Case{"srd2d_a140_dt0.5",
             2,
             Collision::srd,
             10,
             0.5,
             140,
             {416, 24, 0},
             0.00186,
             620,
             20,
             310,
             0.03},
        // The known failure of the 2D molecular-chaos formula at alpha = 90 deg: two independent
        // codes measure nu +12 % to +23 % above it (issue 17; this code +22 to +24 %, lambda 0.5
        // and 1), from correlations between collisions that the formula leaves out. Asserted as
        // an expected deviation: inside the independent codes' range [+12 %, +23 %] widened by
        // 3 standard errors of this run (measured +23.6 +- 2.6 %, so about [+4 %, +31 %]), so
        // a change that moves nu towards the formula or farther from it is seen.
        Case{"srd2d_a90_dt1_expected_deviation",
             2,
             Collision::srd,
             10,
             1.0,
             90,
             {400, 12, 0},
             0.00208,
             280,
             20,
             100,
             0.0,
             0.12,
             0.23},
        // MPC-AT, thermostatted: larger u0 allowed (no heating), Re_k ~ 0.8.
        Case{
            "at2d_dt0.5", 2, Collision::at, 10, 0.5, 90, {100, 24, 0}, 0.00297, 640, 20, 320, 0.05},
        Case{"at3d_dt0.5", 3, Collision::at, 10, 0.5, 90, {16, 16, 16}, 0.01, 280, 20, 140, 0.05},
        // MPC-AT+a: large-n formula in 3D (Kanehl (thesis) eq 4.13-4.14), none in 2D: report only.
        Case{"at_a3d_dt0.5_report",
             3,
             Collision::at_a,
             10,
             0.5,
             90,
             {16, 16, 16},
             0.0075,
             280,
             20,
             140,
             0.0},
        Case{"at_a2d_dt0.5_report",
             2,
             Collision::at_a,
             10,
             0.5,
             90,
             {100, 24, 0},
             0.003,
             640,
             20,
             320,
             0.0}),
    [](const auto &info) {
      std::string n = info.param.name;
      std::replace(n.begin(), n.end(), '.', '_');
      return n;
    });
