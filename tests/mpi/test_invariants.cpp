// Every branch of the runtime invariant check fires: a NaN velocity or position, a runaway
// speed, a particle outside the channel, a momentum drift (periodic box, constant force, slip
// channel). A fault is injected on the last rank after a few steps; every rank throws
// ExitCode::invariant, the injecting rank naming the step, itself and what broke, the others
// saying another rank found it. (The lost-particle branch: test_reductions.cpp; exit code 3
// from the command line: tests/cli/invariants.sh.)
#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <functional>
#include <limits>
#include <string>
#include <utility>

using namespace narrows;

namespace {

using narrows::testing::world_rank;
using narrows::testing::world_size;

scene::Scene periodic_scene() {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 4;
  s.domain.size = {13.0, 8.0, 0.0}; // uneven slabs on 2, 3 and 4 ranks
  s.fluid.density = 5.0;
  s.fluid.dt = 0.5;
  return s;
}

scene::Scene channel_scene(bool slip, bool virtual_particles) {
  scene::Scene s = periodic_scene();
  s.walls = scene::Walls{slip, virtual_particles, scene::VirtualFlow::rest};
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.01, 0.0, 0.0}, 0.0};
  return s;
}

constexpr int steps_before = 3;

// What the check said on this rank: empty if it did not throw.
struct Outcome {
  bool threw = false;
  ExitCode code = ExitCode::ok;
  std::string message;
};

// Runs steps_before steps, lets `inject` change the fluid of the last rank, and checks.
Outcome inject_and_check(const scene::Scene &s, const std::function<void(mpcd::Fluid &)> &inject) {
  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const mpcd::InvariantCheck check(sim);
  for (int i = 0; i < steps_before; ++i)
    sim.advance();
  EXPECT_NO_THROW(check.check(sim)) << "the unbroken run must pass";
  if (world_rank() == world_size() - 1) {
    EXPECT_GT(sim.fluid().size(), 0u);
    inject(sim.fluid());
  }
  Outcome out;
  try {
    check.check(sim);
  } catch (const Error &e) {
    out = {true, e.code(), e.what()};
  }
  return out;
}

// Every rank threw exit code 3 naming the step and itself; the last rank (or with `global`,
// a total every rank computes, each rank) names `what`, the others say another rank found it.
void expect_caught(const Outcome &o, const std::string &what, bool global = false) {
  ASSERT_TRUE(o.threw) << "rank " << world_rank() << ": not detected";
  EXPECT_EQ(o.code, ExitCode::invariant);
  EXPECT_EQ(static_cast<int>(ExitCode::invariant), 3);
  const int last = world_size() - 1;
  const std::string head = "invariant broken at step " + std::to_string(steps_before) +
                           " on rank " + std::to_string(world_rank()) + ": ";
  EXPECT_EQ(o.message.rfind(head, 0), 0u) << o.message;
  if (world_rank() == last || global)
    EXPECT_NE(o.message.find(what), std::string::npos) << o.message;
  else
    EXPECT_NE(o.message.find("another rank found"), std::string::npos) << o.message;
}

const double not_a_number = std::numeric_limits<double>::quiet_NaN();

} // namespace

TEST(Invariants, NanVelocityIsCaught) {
  const auto o =
      inject_and_check(periodic_scene(), [](mpcd::Fluid &f) { f.v[1][0] = not_a_number; });
  expect_caught(o, "velocity nan along axis 1 (allowed: finite");
}

TEST(Invariants, NanPositionIsCaught) {
  const auto o =
      inject_and_check(periodic_scene(), [](mpcd::Fluid &f) { f.x[0][0] = not_a_number; });
  expect_caught(o, "has position nan");
}

TEST(Invariants, RunawaySpeedIsCaught) {
  const auto o = inject_and_check(periodic_scene(),
                                  [](mpcd::Fluid &f) { f.v[0][0] = -1.5 * mpcd::max_speed; });
  expect_caught(o, "velocity -15000 along axis 0 (allowed: finite, |v| <= 10000)");
}

TEST(Invariants, ParticleOutsideTheChannelIsCaught) {
  for (const auto &[y, printed] : {std::pair{-0.25, "-0.25"}, std::pair{8.25, "8.25"}}) {
    const auto o =
        inject_and_check(channel_scene(false, true), [y = y](mpcd::Fluid &f) { f.x[1][0] = y; });
    expect_caught(o, std::string("is outside the channel at y = ") + printed +
                         " (allowed: 0 <= y <= 8)");
  }
}

// A momentum drift of 1e-6 (a million times the rounding allowance of ~N 2^-40 per step) in a
// box that conserves momentum.
TEST(Invariants, MomentumDriftIsCaught) {
  const auto o = inject_and_check(periodic_scene(), [](mpcd::Fluid &f) { f.v[0][0] += 1e-6; });
  expect_caught(o, "total momentum along axis 0", true);
}

// With a constant force the expected momentum grows by N g t: the unbroken run passes (checked
// in inject_and_check), a drift on top is caught.
TEST(Invariants, MomentumDriftUnderAConstantForceIsCaught) {
  scene::Scene s = periodic_scene();
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.02, -0.01, 0.0}, 0.0};
  const auto o = inject_and_check(s, [](mpcd::Fluid &f) { f.v[1][0] -= 1e-6; });
  expect_caught(o, "total momentum along axis 1", true);
}

// Slip walls without virtual particles only reverse v_y: the momentum along the walls is the
// force impulse and is checked (a drift is caught). With no-slip walls or virtual particles
// the walls take momentum that the kernels do not tally, so only the other branches apply
// there (see invariants.cpp).
TEST(Invariants, MomentumDriftAlongSlipWallsIsCaught) {
  const auto o =
      inject_and_check(channel_scene(true, false), [](mpcd::Fluid &f) { f.v[0][0] += 1e-6; });
  expect_caught(o, "total momentum along axis 0", true);
}
