// The MPCD step is its stage list: the pipeline `narrows check`/`info` print (describe_simulation,
// the function behind describe_scene) is that list, and advance() runs exactly it, in the
// printed order. A stage added to or taken out of a built simulation's list shows in both. One
// scene per coupling (none, MD, no-slip), so that each coupling's stages are seen at its hooks.
#include "narrows/engines/mpcd/info.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::world_size;

enum class Coupled { none, md, no_slip };

struct Case {
  const char *name;
  Coupled colloids;
};

void PrintTo(const Case &c, std::ostream *os) { *os << c.name; }

scene::Scene make_scene(Coupled colloids) {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 17;
  s.run.steps = 10;
  s.domain.size = {25, 10, 0}; // uneven slabs on 2, 3 and 4 ranks
  s.fluid.density = 6.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 120.0;
  s.fluid.sort_every = 3;
  s.output.observables = {"temperature"};
  if (colloids == Coupled::none) { // Kolmogorov flow, per-layer thermostat
    s.body_force = scene::BodyForce{scene::ForceKind::sine, {0, 0, 0}, 0.05};
    s.thermostat = scene::Thermostat{scene::ThermostatKind::layers, 0.2};
    return s;
  }
  // A channel with virtual particles and colloids in it.
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.01, 0.0, 0.0}, 0};
  s.walls = scene::Walls{false, true, scene::VirtualFlow::rest};
  scene::Colloids c;
  c.radius = 2.0;
  c.count = 4;
  c.placement = scene::ColloidPlacement::random;
  c.md_substeps = 50;
  if (colloids == Coupled::no_slip) { // bounce-back, ghost particles, hard contacts
    c.coupling = scene::ColloidCoupling::no_slip;
    c.contacts = scene::ColloidContacts::hard;
    c.gravity = {0.0, -0.02, 0.0};
    s.fluid.collision = scene::Collision::at_a;
    s.fluid.dt = 0.1; // the explicit coupling's stability bound (docs/scenes.md)
  }
  s.colloids = c;
  return s;
}

// The stages as describe_simulation prints them, without their numbers (which must count 1, 2,
// 3, ... down the block "pipeline (per step):").
std::vector<std::string> printed_stages(const mpcd::MpcdSimulation &sim) {
  const std::vector<std::string> lines = mpcd::describe_simulation(sim);
  auto line = std::find(lines.begin(), lines.end(), "pipeline (per step):");
  EXPECT_NE(line, lines.end()) << "no pipeline block";
  std::vector<std::string> names;
  if (line == lines.end())
    return names;
  for (++line; line != lines.end(); ++line) {
    const std::string number = "  " + std::to_string(names.size() + 1) + ". ";
    if (line->rfind(number, 0) != 0)
      break;
    names.push_back(line->substr(number.size()));
  }
  return names;
}

bool starts_with(const std::string &s, const std::string &prefix) {
  return s.rfind(prefix, 0) == 0;
}

// The stages each scene must have, by the start of their lines, in order: the engine's and, at
// their hooks, the coupling's.
std::vector<std::string> expected_prefixes(Coupled colloids, bool slabs) {
  std::vector<std::string> p;
  if (colloids == Coupled::md)
    p.push_back("MD: forces, ghost colloids"); // before_stream
  if (colloids == Coupled::no_slip)
    p.push_back("no-slip colloids: 4 (r 2) move with event-driven rough hard-sphere contacts");
  p.push_back(colloids == Coupled::none ? "stream (sine force" : "stream with no-slip bounce-back");
  if (colloids == Coupled::md) // after_stream
    p.push_back("MD: 4 colloids (r 2, M ");
  if (colloids == Coupled::no_slip)
    p.push_back("bounce-back of fluid that entered a colloid");
  p.push_back("grid shift");
  if (slabs) {
    p.push_back("bin into cells, list particles leaving the slab");
    p.push_back("migrate to slab owners (" + std::to_string(world_size()) +
                " ranks), bin arrivals");
  } else {
    p.push_back("bin into cells");
  }
  if (colloids == Coupled::no_slip) // after_bin
    p.push_back("ghost particles in the cells cut by colloid surfaces (density 6,");
  if (colloids != Coupled::none)
    p.push_back("virtual particles in cells cut by the walls (at rest)");
  p.push_back(colloids == Coupled::no_slip ? "collide MPC-AT+a (kT 1" : "collide SRD (angle 120");
  if (colloids == Coupled::no_slip) { // within_collide, then MPC-AT+a's particle pass
    p.push_back("ghost particles' momentum and angular momentum change to the colloids");
    p.push_back("collide MPC-AT+a: the particles' new velocities");
  }
  if (colloids == Coupled::none)
    p.push_back("thermostat: rescale velocities");
  p.push_back("sort by cell (every 3 steps)");
  return p;
}

class StageList : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(StageList, CheckPrintsTheStagesThatRun) {
  const Case c = GetParam();
  mpcd::MpcdSimulation sim(make_scene(c.colloids), MPI_COMM_WORLD);
  const std::vector<std::string> printed = printed_stages(sim);

  // The coupling's stages at its hooks, among the engine's.
  const auto prefixes = expected_prefixes(c.colloids, world_size() > 1);
  ASSERT_EQ(printed.size(), prefixes.size()) << ::testing::PrintToString(printed);
  for (std::size_t i = 0; i < printed.size(); ++i)
    EXPECT_TRUE(starts_with(printed[i], prefixes[i]))
        << "stage " << i + 1 << " is \"" << printed[i] << "\", expected \"" << prefixes[i]
        << "...\"";

  // Every printed stage runs once per step, in the printed order, and nothing else runs.
  std::vector<std::string> ran;
  for (mpcd::Stage &stage : sim.stages())
    stage.run = [&ran, name = stage.name, run = stage.run](std::uint64_t step) {
      ran.push_back(name);
      run(step);
    };
  sim.advance();
  sim.advance();
  std::vector<std::string> twice = printed;
  twice.insert(twice.end(), printed.begin(), printed.end());
  EXPECT_EQ(ran, twice);

  // A stage added after the collision and the sort taken out: the print and the step follow.
  auto &list = sim.stages();
  const auto collide = std::find_if(list.begin(), list.end(), [](const mpcd::Stage &s) {
    return starts_with(s.name, "collide");
  });
  ASSERT_NE(collide, list.end());
  const std::string added = "count the collisions (a stage the test adds)";
  int added_runs = 0;
  list.insert(collide + 1, {added, [&ran, &added_runs, added](std::uint64_t) {
                              ran.push_back(added);
                              ++added_runs;
                            }});
  const auto sort = std::find_if(list.begin(), list.end(), [](const mpcd::Stage &s) {
    return starts_with(s.name, "sort by cell");
  });
  ASSERT_NE(sort, list.end());
  list.erase(sort);
  std::vector<std::string> changed = printed;
  const auto at = std::find_if(changed.begin(), changed.end(),
                               [](const std::string &s) { return starts_with(s, "collide"); });
  changed.insert(at + 1, added);
  changed.pop_back(); // the sort was the last stage
  EXPECT_EQ(printed_stages(sim), changed);
  ran.clear();
  sim.advance();
  EXPECT_EQ(ran, changed);
  EXPECT_EQ(added_runs, 1);
}

INSTANTIATE_TEST_SUITE_P(Couplings, StageList,
                         ::testing::Values(Case{"no_colloids", Coupled::none},
                                           Case{"md", Coupled::md},
                                           Case{"no_slip", Coupled::no_slip}),
                         [](const auto &info) { return std::string(info.param.name); });
