// Hard cases of the MPCD engine (ctest -L hard, README "Hard cases"):
// - the time step below which `narrows check` warns, per collision rule (the
//   mean free path dt sqrt(kT) < 0.5 a leaves kinetic theory), found by bisection of
//   regime_warnings, per rule and at two temperatures;
// - 10^5 steps of every MPCD scene class of run/ at reduced size, with the run's invariant
//   check (count, ids, no NaN or runaway speed, momentum where conserved) every 100 steps.
#include "narrows/engines/mpcd/info.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace {

using namespace narrows;

bool warns_about_mean_free_path(const scene::Scene &s) {
  for (const auto &w : mpcd::regime_warnings(s))
    if (w.find("mean free path") != std::string::npos)
      return true;
  return false;
}

// A channel of run/ with the given rule, dt and kT.
scene::Scene channel(const std::string &file, const std::string &rule, double dt, double kT) {
  return scene::load_scene(std::string(NARROWS_SOURCE_DIR) + "/run/" + file,
                           {"fluid.collision=" + rule, "fluid.dt=" + std::to_string(dt),
                            "fluid.kT=" + std::to_string(kT)});
}

// check warns about the time step only through the mean free path, and only for the rules with
// a kinetic-theory viscosity (srd, at; at+a in 3D): there is no upper limit on dt.
TEST(HardCaseTimeStep, CheckWarnsBelowTheMeanFreePathLimitForEachRule) {
  struct Case {
    const char *file, *rule;
    bool has_theory;
  };
  for (const Case c :
       {Case{"quickstart.toml", "srd", true}, Case{"quickstart.toml", "at", true},
        Case{"ata_fluid_table5_1_3d.toml", "at+a", true}, Case{"quickstart.toml", "at+a", false},
        Case{"quickstart.toml", "random-permute", false},
        Case{"quickstart.toml", "random-maxwell", false}})
    for (const double kT : {1.0, 4.0}) {
      // Bisection for the time step at which the warning stops: below it check warns.
      double lo = 1e-3, hi = 2.0;
      ASSERT_EQ(warns_about_mean_free_path(channel(c.file, c.rule, lo, kT)), c.has_theory)
          << c.rule << " in " << c.file;
      ASSERT_FALSE(warns_about_mean_free_path(channel(c.file, c.rule, hi, kT))) << c.rule;
      if (!c.has_theory) {
        std::printf("[ measured ] %s (%s) kT %g: check never warns about dt (no kinetic "
                    "theory)\n",
                    c.rule, c.file, kT);
        continue;
      }
      for (int i = 0; i < 50; ++i) {
        const double mid = 0.5 * (lo + hi);
        (warns_about_mean_free_path(channel(c.file, c.rule, mid, kT)) ? lo : hi) = mid;
      }
      std::printf("[ measured ] %s (%s) kT %g: check warns for dt < %.6f\n", c.rule, c.file, kT,
                  hi);
      EXPECT_NEAR(hi, 0.5 / std::sqrt(kT), 1e-5) << c.rule << " kT " << kT;
    }
}

struct SceneClass {
  const char *file;
  std::vector<std::string> reduce; // --set overrides to a tiny box
};

void PrintTo(const SceneClass &c, std::ostream *os) { *os << c.file; }

class HardCaseLongRun : public ::testing::TestWithParam<SceneClass> {};

TEST_P(HardCaseLongRun, InvariantsHoldEvery100StepsFor1e5Steps) {
  const SceneClass c = GetParam();
  const scene::Scene s =
      scene::load_scene(std::string(NARROWS_SOURCE_DIR) + "/run/" + c.file, c.reduce);
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  const mpcd::InvariantCheck invariants(sim);
  const auto start = std::chrono::steady_clock::now();
  constexpr int steps = 100000;
  for (int step = 1; step <= steps; ++step) {
    sim.advance();
    if (step % 100 == 0) {
      ASSERT_NO_THROW(invariants.check(sim)) << c.file << " step " << step;
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ measured ] %s: %d steps, %zu particles, %.1f s\n", c.file, steps,
              sim.fluid().size(), seconds);
}

const std::vector<std::string> tiny2d{"domain.size=[8.0, 6.0]", "fluid.density=3"};

INSTANTIATE_TEST_SUITE_P(
    RunScenes, HardCaseLongRun,
    ::testing::Values(
        SceneClass{"quickstart.toml", tiny2d},        // SRD channel, body force, virtual particles
        SceneClass{"strong_scaling.toml", tiny2d},    // periodic SRD box
        SceneClass{"poiseuille_fig3_7.toml", tiny2d}, // SRD channel of Tabatabaei (2008) ch.3
        SceneClass{"ata_fluid_table5_1_2d.toml", tiny2d}, // MPC-AT+a channel
        SceneClass{"ata_fluid_table5_1_3d.toml",
                   {"domain.size=[4.0, 4.0, 4.0]", "fluid.density=2"}}, // 3D AT+a slit
        SceneClass{"colloids_conservation.toml",
                   {"domain.size=[16.0, 8.0]", "fluid.density=3", "colloids.count=2",
                    "colloids.md_substeps=5"}}, // colloids, periodic, no force
        SceneClass{"sedimentation_fig4_10.toml",
                   {"domain.size=[12.0, 10.0]", "fluid.density=3", "colloids.count=1",
                    "colloids.md_substeps=5"}}, // colloids sedimenting in a channel
        SceneClass{"random_solvent_wake.toml",
                   {"domain.size=[12.0, 10.0]", "fluid.density=3", "colloids.md_substeps=5",
                    "output.trajectory_every=0"}}), // random solvent + colloid
    [](const auto &info) {
      std::string name = info.param.file;
      name = name.substr(0, name.find('.'));
      return name;
    });

} // namespace
