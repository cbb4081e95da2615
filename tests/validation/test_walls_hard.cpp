// Hard cases for the walls (issue 4): a body force strong enough for Ma ~ 0.5 at the channel
// centre for 10^4 steps, with a tenth of the particles starting exactly on a wall (some at
// rest, some moving out). The run's own invariant check (no particle outside the channel, no
// NaN, count and id set) must hold at every check, and the flow must really reach Ma ~ 0.5.
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/engines/mpcd/transport_theory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace narrows;

namespace {

struct Case {
  const char *name;
  int dim;
  scene::Collision rule;
  bool slip;
};

class WallsHard : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(WallsHard, StrongForceAndParticlesOnTheWalls) {
  const Case c = GetParam();
  scene::Scene s;
  s.run.dimensions = c.dim;
  s.run.seed = 17;
  s.domain.size = c.dim == 2 ? std::array<double, 3>{40, 8, 0} : std::array<double, 3>{12, 8, 6};
  s.fluid.collision = c.rule;
  s.fluid.density = 5.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 130.0;
  s.walls = scene::Walls{c.slip, true};
  // g from the Poiseuille centre velocity u0 = g L^2 / (8 nu) = 0.5 c_s (kinetic theory nu; for
  // AT+a the 3D large-n formula is used in 2D too, only the order of magnitude matters).
  const double cs = std::sqrt((c.dim + 2.0) / c.dim);
  const auto nu =
      mpcd::viscosity(c.rule == scene::Collision::at_a ? scene::Collision::at : c.rule, c.dim,
                      s.fluid.density, s.fluid.dt, 130.0 * std::numbers::pi / 180, 1.0);
  ASSERT_TRUE(nu.has_value());
  const double L = s.domain.size[1];
  const double g = 8.0 * nu->total() * 0.5 * cs / (L * L);
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {g, 0.0, 0.0}, 0.0};

  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  auto &f = sim.fluid();
  for (std::size_t i = 0; i < f.size(); i += 10) {
    const bool top = (i / 10) % 2 == 1;
    f.x[1][i] = top ? L : 0.0;
    if ((i / 10) % 3 == 0)
      f.v[1][i] = 0.0; // at rest on the wall
    else
      f.v[1][i] = top ? std::abs(f.v[1][i]) : -std::abs(f.v[1][i]); // moving out
  }
  const mpcd::InvariantCheck invariants(sim);
  double centre_sum = 0.0;
  long centre_count = 0;
  for (int step = 1; step <= 10000; ++step) {
    sim.advance();
    if (step % 100 == 0) {
      ASSERT_NO_THROW(invariants.check(sim)) << "step " << step;
    }
    if (step > 2000 && step % 10 == 0)
      for (std::size_t i = 0; i < f.size(); ++i)
        if (std::abs(f.x[1][i] - 0.5 * L) < 1.0) {
          centre_sum += f.v[0][i];
          ++centre_count;
        }
  }
  const double mach = centre_sum / centre_count / cs;
  std::printf("[ measured ] %s: centre Ma = %.3f, kT = %.3f\n", c.name, mach,
              analysis::temperature(f, MPI_COMM_SELF));
  // Slip walls do not hold the fluid back: it accelerates freely (only the virtual particles
  // drag it), so only the no-slip cases reach the Poiseuille Ma.
  if (!c.slip) {
    EXPECT_GT(mach, 0.35);
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, WallsHard,
                         ::testing::Values(Case{"srd2d_noslip", 2, scene::Collision::srd, false},
                                           Case{"srd2d_slip", 2, scene::Collision::srd, true},
                                           Case{"srd3d_noslip", 3, scene::Collision::srd, false},
                                           Case{"at_a2d_noslip", 2, scene::Collision::at_a, false},
                                           Case{"at3d_noslip", 3, scene::Collision::at, false}),
                         [](const auto &info) { return std::string(info.param.name); });
