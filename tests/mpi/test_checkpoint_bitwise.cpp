// Checkpoint/restart continues bitwise: N steps straight equal N/2 steps, a checkpoint, a
// restart and N/2 more, on 2 ranks, on 1 rank (MPI_COMM_SELF on rank 0), written on 2 ranks
// and continued on 1, and written on 1 and continued on 2. All particles compared by id.
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "../common/state_by_id.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace narrows;

namespace {

int rank_in(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

using narrows::testing::state_by_id;

struct Case {
  const char *name;
  int dim;
  scene::Collision rule;
  bool sine;
  bool walls = false; // no-slip walls with virtual particles
};

scene::Scene make_scene(const Case &c) {
  scene::Scene s;
  s.run.dimensions = c.dim;
  s.run.seed = 77;
  s.domain.size = c.dim == 2 ? std::array<double, 3>{24, 10, 0} : std::array<double, 3>{12, 6, 6};
  s.fluid.collision = c.rule;
  s.fluid.density = 5.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 120.0;
  s.fluid.sort_every = 7;
  s.body_force = c.sine ? scene::BodyForce{scene::ForceKind::sine, {0, 0, 0}, 0.05}
                        : scene::BodyForce{scene::ForceKind::constant, {0.01, -0.003, 0.002}, 0};
  if (c.walls)
    s.walls = scene::Walls{};
  s.text = "# test scene\n";
  return s;
}

constexpr int steps = 300; // odd half (150 is even; sort_every 7 crosses the restart step)

// A directory every rank of WORLD knows.
std::string shared_tmpdir() {
  char buf[256] = {};
  if (rank_in(MPI_COMM_WORLD) == 0) {
    std::string t = (std::filesystem::temp_directory_path() / "narrows-ckpt-XXXXXX").string();
    std::strncpy(buf, t.c_str(), sizeof buf - 1);
    if (mkdtemp(buf) == nullptr)
      buf[0] = '\0';
  }
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

// Runs `steps` steps straight on comm and returns the state on its rank 0.
std::vector<double> straight(const scene::Scene &s, MPI_Comm comm) {
  mpcd::MpcdSimulation sim(s, comm);
  for (int i = 0; i < steps; ++i)
    sim.advance();
  return state_by_id(sim.fluid(), mpcd::particle_count(s), comm);
}

// Runs half the steps on comm and writes a checkpoint.
void first_half(const scene::Scene &s, MPI_Comm comm, const std::string &path) {
  mpcd::MpcdSimulation sim(s, comm);
  for (int i = 0; i < steps / 2; ++i)
    sim.advance();
  io::CheckpointInfo info;
  info.scene_text = s.text;
  info.step = sim.step();
  info.time = sim.time();
  info.seed = s.run.seed;
  info.dimensions = sim.box().dim;
  info.box = sim.box().length;
  io::write_checkpoint(path, info, {mpcd::fluid_fields(sim.fluid())}, comm);
}

// Reads the checkpoint on comm, runs the second half, returns the state on its rank 0.
std::vector<double> second_half(const scene::Scene &s, MPI_Comm comm, const std::string &path) {
  const auto info = io::read_checkpoint_info(path, comm);
  EXPECT_EQ(info.step, steps / 2);
  EXPECT_EQ(info.fluid_particles, mpcd::particle_count(s));
  EXPECT_EQ(info.scene_text, s.text);
  mpcd::MpcdSimulation sim(s, comm, false);
  sim.restore(mpcd::read_fluid(path, info, comm), info.step);
  for (int i = steps / 2; i < steps; ++i)
    sim.advance();
  EXPECT_EQ(sim.step(), steps);
  return state_by_id(sim.fluid(), mpcd::particle_count(s), comm);
}

std::size_t count_differences(const std::vector<double> &a, const std::vector<double> &b) {
  if (a.size() != b.size())
    return std::max(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t j = 0; j < a.size(); ++j)
    differ += std::memcmp(&a[j], &b[j], sizeof(double)) != 0;
  return differ;
}

class CheckpointBitwise : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(CheckpointBitwise, RestartOnAnyRankCountContinuesBitwise) {
  const Case c = GetParam();
  const scene::Scene s = make_scene(c);
  const std::string dir = shared_tmpdir();
  ASSERT_FALSE(dir.empty());
  const bool root = rank_in(MPI_COMM_WORLD) == 0;

  // Reference: 2 ranks straight (bitwise equal to 1 rank, tested by test_slabs_bitwise).
  const auto ref = straight(s, MPI_COMM_WORLD);

  // 2 ranks -> 2 ranks.
  const std::string two = dir + "/two.h5";
  first_half(s, MPI_COMM_WORLD, two);
  const auto two_two = second_half(s, MPI_COMM_WORLD, two);
  if (root) {
    EXPECT_EQ(count_differences(ref, two_two), 0u) << "2 ranks -> 2 ranks";
  }

  // 2 ranks -> 1 rank, and 1 rank -> 1 rank, on rank 0's MPI_COMM_SELF.
  const std::string one = dir + "/one.h5";
  if (root) {
    const auto two_one = second_half(s, MPI_COMM_SELF, two);
    EXPECT_EQ(count_differences(ref, two_one), 0u) << "2 ranks -> 1 rank";
    first_half(s, MPI_COMM_SELF, one);
    const auto one_one = second_half(s, MPI_COMM_SELF, one);
    EXPECT_EQ(count_differences(ref, one_one), 0u) << "1 rank -> 1 rank";
  }
  MPI_Barrier(MPI_COMM_WORLD);

  // 1 rank -> 2 ranks.
  const auto one_two = second_half(s, MPI_COMM_WORLD, one);
  if (root) {
    EXPECT_EQ(count_differences(ref, one_two), 0u) << "1 rank -> 2 ranks";
  }

  // Nothing is left under a temporary name.
  if (root) {
    EXPECT_FALSE(std::filesystem::exists(two + ".tmp"));
    std::filesystem::remove_all(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

INSTANTIATE_TEST_SUITE_P(
    Rules, CheckpointBitwise,
    ::testing::Values(Case{"srd2d_sine", 2, scene::Collision::srd, true},
                      Case{"srd3d_constant", 3, scene::Collision::srd, false},
                      Case{"at_a2d_constant", 2, scene::Collision::at_a, false},
                      Case{"at3d_sine", 3, scene::Collision::at, true},
                      Case{"maxwell2d_constant", 2, scene::Collision::random_maxwell, false},
                      Case{"srd2d_walls", 2, scene::Collision::srd, false, true},
                      Case{"at3d_walls", 3, scene::Collision::at, false, true}),
    [](const auto &info) { return std::string(info.param.name); });
