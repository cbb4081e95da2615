// Poiseuille-channel viscosity (issue 4): walls at y = 0 and y = L_y, force g along x, nu from
// the fitted curvature of the steady profile (Tabatabaei (2008) eq 3.15, Kanehl (thesis)
// eq 4.48-4.49).
//
// - Tabatabaei (2008) fig 3.6 (2D SRD, 25 x 25, n = 10, dt = 0.1, alpha = 90, g = 0.001):
//   standard error <= 2 % and within two standard errors of the theory value 0.755.
// - lambda >= 0.5: SRD 2D and 3D, two angles each, within 3 % of theory at the measured
//   temperature; MPC-AT within 5 % of its formula (thermostatted, theory at kT = 1).
// - Kanehl (thesis) values for MPC-AT+a at small dt (molecular chaos fails there, so the formula is
//   not the reference; the thesis' measurements are), within 5 %.
// Every run also reports the fitted wall velocity (slip) relative to the centre velocity.
// Blocks are several momentum-relaxation times L_y^2/(pi^2 nu) long; the test requires the
// block-average error to be below half the tolerance, so a pass is not luck.
#include "poiseuille.hpp"

#include "narrows/engines/mpcd/transport_theory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

using namespace narrows;

namespace {

enum class Reference { theory, fixed, report };

struct Case {
  const char *name;
  int dim;
  scene::Collision rule;
  double n, dt, angle_deg;
  std::array<double, 3> size;
  double g;
  int warmup, blocks, block_steps;
  Reference reference;
  double value;     // the reference value for Reference::fixed
  double tolerance; // relative (theory, fixed); for fig 3.6: in standard errors
};

class Poiseuille : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(Poiseuille, ViscosityFromTheProfile) {
  const Case c = GetParam();
  const auto s = validation::channel_scene(c.dim, c.rule, c.n, c.dt, c.angle_deg, c.size, c.g);
  const auto r = validation::measure_poiseuille(s, c.warmup, c.blocks, c.block_steps);
  const bool thermostatted = c.rule != scene::Collision::srd;
  const auto theory = mpcd::viscosity(
      c.rule, c.dim, c.n, c.dt, c.angle_deg * std::numbers::pi / 180, thermostatted ? 1.0 : r.kT);
  double reference = c.value;
  if (c.reference == Reference::theory) {
    ASSERT_TRUE(theory.has_value());
    reference = theory->total();
  }
  const double dev = r.nu / reference - 1.0;
  std::printf("[ measured ] %s: L_y = %g, nu = %.4f +- %.4f (%.2f %%), reference %.4f (%s), "
              "deviation %+.2f %% (%.1f sigma); kT %.4f, v0 %.4f, wall velocity %+.2f +- %.2f %% "
              "of v0\n",
              c.name, c.size[1], r.nu, r.nu_error, 100 * r.nu_error / r.nu, reference,
              c.reference == Reference::theory  ? "theory at measured kT"
              : c.reference == Reference::fixed ? "Kanehl (thesis) measurement"
                                                : "for comparison",
              100 * dev, std::abs(r.nu - reference) / r.nu_error, r.kT, r.v0, 100 * r.slip,
              100 * r.slip_error);
  double dmin = 1e300, dmax = 0;
  for (double d : r.density) {
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
  }
  // The ideal-gas density stays uniform up to the walls: bounce-back keeps it flat. Checked at
  // lambda >= 0.5, where particles cross the channel many times per run; at dt = 0.01 a row of
  // ~10^3 particles keeps its initial Poisson excess (~3 %) for longer than the run.
  std::printf("[ measured ] %s: density per row / n from %.4f to %.4f\n", c.name, dmin / c.n,
              dmax / c.n);
  if (c.dt >= 0.5) {
    EXPECT_LT(dmax / c.n - 1.0, 0.02);
    EXPECT_GT(dmin / c.n - 1.0, -0.02);
  }
  switch (c.reference) {
  case Reference::theory:
  case Reference::fixed:
    EXPECT_LT(r.nu_error / r.nu, 0.5 * c.tolerance) << "run too short to test the tolerance";
    EXPECT_LT(std::abs(dev), c.tolerance);
    break;
  case Reference::report:
    EXPECT_LT(r.nu_error / r.nu, 0.05);
    break;
  }
}

// Tabatabaei (2008) fig 3.6 asks for a standard error <= 2 % and agreement within two of them.
TEST(PoiseuilleTabatabaei, Figure3_6) {
  const auto s =
      validation::channel_scene(2, scene::Collision::srd, 10, 0.1, 90, {25, 25, 0}, 0.001);
  const auto r = validation::measure_poiseuille(s, 20000, 80, 2000);
  const double theory = 0.755;
  std::printf("[ measured ] Tabatabaei (2008) fig 3.6: nu = %.4f +- %.4f (%.2f %%), theory "
              "%.3f (%.1f standard errors), Tabatabaei measured 0.729; wall velocity %+.2f +- "
              "%.2f %% of v0 = %.4f; nu from v_max = g L^2/(8 v_max) would be %.4f\n",
              r.nu, r.nu_error, 100 * r.nu_error / r.nu, theory,
              std::abs(r.nu - theory) / r.nu_error, 100 * r.slip, 100 * r.slip_error, r.v0,
              0.001 * 625 / (8 * r.v0));
  EXPECT_LE(r.nu_error / r.nu, 0.02);
  EXPECT_LT(std::abs(r.nu - theory), 2.0 * r.nu_error);
}

// Virtual particles are what hold the fluid at the wall: without them the cut cells are
// partly empty and the fitted wall velocity is several times larger. At rest
// (Tabatabaei (2008) eq 3.14) they leave a slip of a few percent of v0 (slip length ~0.2 a at
// lambda = 0.1: the cut cell averages the fluid with resting virtual particles, not with the flow's
// continuation); continuing the flow antisymmetrically through the wall (virtual_flow = mirror)
// brings it below 2 % of v0 (issue 4, acceptance 4).
TEST(PoiseuilleVirtualParticles, HoldTheFluidAtTheWall) {
  auto s = validation::channel_scene(2, scene::Collision::srd, 10, 0.1, 90, {50, 25, 0}, 0.001);
  const auto rest = validation::measure_poiseuille(s, 20000, 40, 2000);
  s.walls->virtual_flow = scene::VirtualFlow::mirror;
  const auto mirror = validation::measure_poiseuille(s, 20000, 100, 2000);
  s.walls->virtual_particles = false;
  const auto none = validation::measure_poiseuille(s, 20000, 40, 2000);
  std::printf("[ measured ] wall velocity / v0: virtual particles at rest %+.2f +- %.2f %%, "
              "mirror flow %+.2f +- %.2f %%, none %+.2f +- %.2f %% (kT %.3f, %.3f, %.3f: "
              "without them nothing removes the viscous heat); nu %.4f, %.4f, %.4f\n",
              100 * rest.slip, 100 * rest.slip_error, 100 * mirror.slip, 100 * mirror.slip_error,
              100 * none.slip, 100 * none.slip_error, rest.kT, mirror.kT, none.kT, rest.nu,
              mirror.nu, none.nu);
  EXPECT_GT(none.slip, 4.0 * rest.slip);
  EXPECT_GT(none.slip - rest.slip, 5.0 * std::hypot(rest.slip_error, none.slip_error));
  EXPECT_LT(std::abs(mirror.slip), 0.02);
  EXPECT_LT(mirror.slip_error, 0.01) << "run too short to test the 2 % bound";
  // The mirror flow changes the boundary, not the fluid: nu agrees with the theory 0.7556.
  EXPECT_LT(std::abs(mirror.nu / 0.7556 - 1.0), 3.0 * mirror.nu_error / mirror.nu);
}

using scene::Collision;
INSTANTIATE_TEST_SUITE_P(
    Rules, Poiseuille,
    ::testing::Values(
        // SRD 2D, lambda = 1, two angles (v0 ~ 0.05-0.08).
        Case{"srd2d_a130_dt1",
             2,
             Collision::srd,
             10,
             1.0,
             130,
             {50, 25, 0},
             0.0006,
             10000,
             60,
             1000,
             Reference::theory,
             0,
             0.03},
        Case{"srd2d_a140_dt1",
             2,
             Collision::srd,
             10,
             1.0,
             140,
             {50, 25, 0},
             0.0006,
             10000,
             60,
             1000,
             Reference::theory,
             0,
             0.03},
        // SRD 3D slit, lambda = 1, two angles.
        Case{"srd3d_a90_dt1",
             3,
             Collision::srd,
             10,
             1.0,
             90,
             {20, 16, 10},
             0.0028,
             500,
             40,
             200,
             Reference::theory,
             0,
             0.03},
        Case{"srd3d_a130_dt1",
             3,
             Collision::srd,
             10,
             1.0,
             130,
             {20, 16, 10},
             0.0028,
             500,
             40,
             200,
             Reference::theory,
             0,
             0.03},
        // MPC-AT, lambda = 0.5.
        Case{"at2d_dt0.5",
             2,
             Collision::at,
             10,
             0.5,
             0,
             {50, 25, 0},
             0.0006,
             2000,
             40,
             500,
             Reference::theory,
             0,
             0.05},
        Case{"at3d_dt0.5",
             3,
             Collision::at,
             10,
             0.5,
             0,
             {16, 16, 10},
             0.0014,
             1000,
             25,
             300,
             Reference::theory,
             0,
             0.05},
        // MPC-AT+a, Kanehl (thesis) tables 5.1 and 6.1. At dt = 0.01 the viscosity is large and the
        // profile small against the thermal noise: 10 blocks at g = 0.029 scattered by 4.5 %
        // from seed to seed (6 seeds), so half the 5 % tolerance was not reached; g is 1.5 times
        // that (v0 ~ 0.17, Re = v0 L / nu ~ 0.5; the Poiseuille profile is exact at any Re) and
        // 20 blocks give ~2 %.
        Case{"at_a3d_dt0.01_n10_seed",
             3,
             Collision::at_a,
             10,
             0.01,
             0,
             {10, 10, 10},
             0.044,
             3000,
             20,
             1000,
             Reference::fixed,
             3.15,
             0.05},
        Case{"at_a2d_dt0.02_n25_seed",
             2,
             Collision::at_a,
             25,
             0.02,
             0,
             {20, 20, 0},
             0.008,
             3000,
             20,
             1500,
             Reference::fixed,
             1.98,
             0.05},
        // Kanehl (thesis) table 5.1 gives 3.22 here, which its own 2D value at dt = 0.02, n = 25
        // does not support (nu_coll ~ 1/dt predicts ~3.9); reported, see the issue note.
        // (g and blocks raised as for the 3D case: 10 blocks at g = 0.026 gave errors of 3-6 %.)
        Case{"at_a2d_dt0.01_n50_seed_report",
             2,
             Collision::at_a,
             50,
             0.01,
             0,
             {20, 10, 0},
             0.039,
             3000,
             20,
             1000,
             Reference::report,
             3.22,
             0},
        // Tabatabaei (2008) fig 3.7 (20 x 10, n = 5, dt = 0.1, alpha = 90); g = 0.004 instead of
        // the dissertation's 0.001 for signal (Ma 0.06, still linear); reported against 0.680.
        Case{"srd2d_fig3_7_report",
             2,
             Collision::srd,
             5,
             0.1,
             90,
             {20, 10, 0},
             0.004,
             5000,
             100,
             2000,
             Reference::report,
             0.680,
             0}),
    [](const auto &info) {
      std::string n = info.param.name;
      std::replace(n.begin(), n.end(), '.', '_');
      return n;
    });
