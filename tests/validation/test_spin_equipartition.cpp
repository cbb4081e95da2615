// Issue 33 item 1: free no-slip colloids (Kanehl (thesis) §4.2.1) in equilibrium carry kT per
// degree of freedom, translational and rotational, for each collision rule, in 2D and 3D, at a
// short and a long time step.
//
// Several colloids (hard contacts keep them apart) in a periodic box of fluid at rest. Each step
// the colloids' kinetic temperatures T_U = sum M |U|^2 / (d K) and T_W = sum I |Omega|^2 /
// (r K) (r = 1 in 2D, 3 in 3D) are sampled. The total momentum of the box is conserved and
// zero, so each colloid's translational variance is kT/M (1 - M/M_total) per axis (the
// constraint removes a share M/M_total of its degrees of freedom; ~1 % here): T_U is compared
// with kT (1 - M/M_total). Nothing constrains the spins (a periodic box does not conserve
// angular momentum). The fluid's own kinetic temperature is printed beside them: the ghost
// particles are drawn at the scene's kT, so they hold the fluid there.
//
// The colloids are light (M = 0.25 of the displaced fluid): their velocities decorrelate in a
// few steps at dt = 0.05 and a few tens at dt = 0.005, so a short run gives small errors, and
// the exchange is stressed (G/M per step is large: the explicit change dX = dP/M runs away at
// dt = 0.05, and is hot at dt = 0.005). 2D: 8 disks of radius 2 in 32 x 32, n = 10, 32000 steps;
// 3D: 6 spheres of radius 2 in 12^3, n = 5, 16000 steps (~6-14 s a case).
// Errors: the spread of 20 block means (blocks of 1600 or 800 steps, >> the correlation
// time). Tolerance: within 4 sigma and within 2 % (the acceptance), sigma asserted below
// 0.6 % so that the sigma bound bites (4 sigma <= 2.4 %). 4, not 3: the suite makes 24 such
// checks, and at 3 sigma each a correct code fails one of them in 16 runs (1 - 0.9973^24 =
// 6.3 %); at 4 sigma in 660 (0.15 %). MPC-AT+a 2D at dt = 0.05 sits at +1.0-1.1 % in
// translation (2.8 and 3.05 sigma in two realisations): a residual of the midpoint exchange at
// the long step, within the 2 % bound.
//
// NARROWS_SPIN="rule dim dt radius count L density steps [explicit]" runs one case of the map
// through DISABLED_SpinMap (--gtest_also_run_disabled_tests).
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "fluid_scene.hpp"
#include "poiseuille.hpp" // mean_of, standard_error

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace narrows;

namespace {

struct Case {
  scene::Collision rule;
  int dim;
  double dt;
  double radius = 2.0;
  int count = 8;
  double length = 32.0;
  double density = 10.0;
  int steps = 20000;
  bool implicit = true;
  double mass_ratio = 0.25; // colloid mass / displaced fluid mass
};

struct Result {
  double trans, trans_err, rot, rot_err, fluid_kT, expected_trans;
};

using validation::mean_of;
using validation::standard_error;

Result run(const Case &k) {
  const double L = k.length;
  scene::Scene s = validation::fluid_scene(k.dim, k.rule, k.density, k.dt, 130.0,
                                           {L, L, k.dim == 3 ? L : 0.0}, 17);
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::hard;
  c.exchange_implicit = k.implicit;
  c.radius = k.radius;
  const double volume = k.dim == 2 ? std::numbers::pi * k.radius * k.radius
                                   : 4.0 / 3.0 * std::numbers::pi * std::pow(k.radius, 3);
  c.mass = k.mass_ratio * k.density * volume;
  c.count = k.count;
  c.placement = scene::ColloidPlacement::random;
  s.colloids = c;
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  const int warmup = k.steps / 10, blocks = 20, block_steps = k.steps / blocks;
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  std::vector<double> bt, br;
  double fluid_kT = 0.0;
  int fluid_samples = 0;
  const int r = k.dim == 2 ? 1 : 3;
  for (int b = 0; b < blocks; ++b) {
    double st = 0.0, sr = 0.0;
    for (int i = 0; i < block_steps; ++i) {
      sim.advance();
      const colloids::Colloids col = sim.gather_colloids();
      double t = 0.0, w = 0.0;
      for (std::size_t a = 0; a < col.size(); ++a) {
        for (int d = 0; d < k.dim; ++d)
          t += col.mass[a] * col.v[d][a] * col.v[d][a];
        const double inertia = colloids::moment_of_inertia(col, a);
        for (int d = k.dim == 2 ? 2 : 0; d < 3; ++d)
          w += inertia * col.omega[d][a] * col.omega[d][a];
      }
      st += t / (k.dim * static_cast<double>(col.size()));
      sr += w / (r * static_cast<double>(col.size()));
      if (i % 50 == 0) {
        const auto &f = sim.fluid();
        double e = 0.0;
        for (int d = 0; d < k.dim; ++d)
          for (std::size_t j = 0; j < f.size(); ++j)
            e += f.v[d][j] * f.v[d][j];
        fluid_kT += e / (k.dim * static_cast<double>(f.size()));
        ++fluid_samples;
      }
    }
    bt.push_back(st / block_steps);
    br.push_back(sr / block_steps);
  }
  const double fluid_mass = static_cast<double>(sim.fluid().size());
  const double total = fluid_mass + k.count * c.mass;
  return {mean_of(bt),        standard_error(bt),       mean_of(br),
          standard_error(br), fluid_kT / fluid_samples, 1.0 - c.mass / total};
}

const char *rule_name(scene::Collision r) {
  return r == scene::Collision::srd ? "srd" : r == scene::Collision::at ? "at" : "at_a";
}

void report(const Case &k, const Result &r) {
  std::printf("%s %dD dt %.3g a %.2g K %d L %.0f n %.0f steps %d %s: M<U^2>/(d kT) = %.4f +- "
              "%.4f (expected %.4f), I<W^2>/(r kT) = %.4f +- %.4f, fluid kT %.4f\n",
              rule_name(k.rule), k.dim, k.dt, k.radius, k.count, k.length, k.density, k.steps,
              k.implicit ? "implicit" : "explicit", r.trans, r.trans_err, r.expected_trans, r.rot,
              r.rot_err, r.fluid_kT);
}

void check(const Case &k) {
  const Result r = run(k);
  report(k, r);
  EXPECT_LT(r.trans_err, 0.006);
  EXPECT_LT(r.rot_err, 0.006);
  const double tol_t = std::min(0.02, 4.0 * r.trans_err), tol_r = std::min(0.02, 4.0 * r.rot_err);
  EXPECT_NEAR(r.trans, r.expected_trans, tol_t) << "translation";
  EXPECT_NEAR(r.rot, 1.0, tol_r) << "rotation";
}

} // namespace

class SpinEquipartition : public ::testing::TestWithParam<Case> {};

TEST_P(SpinEquipartition, TranslationAndRotationCarryKT) { check(GetParam()); }

std::vector<Case> cases() {
  std::vector<Case> out;
  for (int dim : {2, 3})
    for (auto rule : {scene::Collision::srd, scene::Collision::at, scene::Collision::at_a})
      for (double dt : {0.005, 0.05}) {
        Case k{rule, dim, dt};
        if (dim == 3) {
          k.count = 6;
          k.length = 12.0;
          k.density = 5.0;
          k.steps = 16000;
        } else {
          k.steps = 32000;
        }
        out.push_back(k);
      }
  return out;
}

INSTANTIATE_TEST_SUITE_P(Rules, SpinEquipartition, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case> &info) {
                           const Case &k = info.param;
                           return std::string(rule_name(k.rule)) + "_" + std::to_string(k.dim) +
                                  "D_dt" + (k.dt < 0.01 ? "0005" : "005");
                         });

TEST(DISABLED_SpinMap, OneCase) {
  const char *env = std::getenv("NARROWS_SPIN");
  if (!env)
    GTEST_SKIP() << "set NARROWS_SPIN";
  std::istringstream in(env);
  std::string rule, mode;
  Case k{scene::Collision::srd, 2, 0.05};
  in >> rule >> k.dim >> k.dt >> k.radius >> k.count >> k.length >> k.density >> k.steps >>
      k.mass_ratio >> mode;
  k.rule = rule == "srd"  ? scene::Collision::srd
           : rule == "at" ? scene::Collision::at
                          : scene::Collision::at_a;
  k.implicit = mode != "explicit";
  report(k, run(k));
}
