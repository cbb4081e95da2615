// The species table (issue 30 item 3): a per-colloid field added in one line (here a scratch
// field of the test, through species::Extra) travels with its colloid through everything the
// table drives, with no other edit: migration to the rank of the new slab during MPCD steps,
// ghost copies for other ranks, gathering, a checkpoint and a restart from it (on any number of
// ranks; the suite runs it on 2, 3 and 4). Colloids pushed along x by a field cross the uneven
// slab edges of a 25-cell box many times within the test.
#include "narrows/colloids/ghosts.hpp"
#include "narrows/engines/mpcd/colloid_checkpoint.hpp"
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/io/checkpoint.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::world_rank;
using narrows::testing::world_size;

// MD colloids pushed along x (M g = 1): they cross slab edges within tens of steps.
scene::Scene drifting_colloids() {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 3003;
  s.domain.size = {25, 10, 0};
  s.fluid.collision = scene::Collision::srd;
  s.fluid.density = 6.0;
  s.fluid.dt = 0.5;
  s.fluid.angle_deg = 120.0;
  s.fluid.sort_every = 7;
  scene::Colloids col;
  col.radius = 2.0;
  col.count = 4;
  col.placement = scene::ColloidPlacement::random;
  col.gravity = {0.008, 0.001, 0.0};
  col.md_substeps = 50;
  s.colloids = col;
  s.text = "# drifting colloids\n";
  return s;
}

// The scratch value of colloid `id`: nothing else in the state could restore it.
double scratch_of(std::uint64_t id) { return 1000.25 + 17.5 * static_cast<double>(id); }

// Rows of c whose scratch value is not that of their id (rows [first, last)).
std::size_t wrong_scratch(const colloids::Colloids &c, std::size_t first, std::size_t last) {
  const auto &scratch = c.extra.get<double>("scratch");
  std::size_t wrong = scratch.size() == c.size() ? 0 : c.size() + 1;
  for (std::size_t a = first; a < last && a < scratch.size(); ++a) {
    const double want = scratch_of(c.id[a]);
    wrong += std::memcmp(&scratch[a], &want, sizeof want) != 0;
  }
  return wrong;
}

std::size_t sum(std::size_t mine) {
  unsigned long long v = mine, all = 0;
  MPI_Allreduce(&v, &all, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

std::string shared_tmpdir() {
  char buf[256] = {};
  if (world_rank() == 0) {
    std::string t = (std::filesystem::temp_directory_path() / "narrows-species-XXXXXX").string();
    std::strncpy(buf, t.c_str(), sizeof buf - 1);
    if (mkdtemp(buf) == nullptr)
      buf[0] = '\0';
  }
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

} // namespace

TEST(SpeciesTable, AddedFieldMigratesGhostsCheckpointsAndRestarts) {
  const scene::Scene s = drifting_colloids();
  const MPI_Comm comm = MPI_COMM_WORLD;
  mpcd::MpcdSimulation sim(s, comm);
  colloids::Colloids &c = sim.colloids();
  // The one line that adds a field to the colloid species:
  auto &scratch = c.extra.add<double>("scratch", species::everywhere, c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    scratch[a] = scratch_of(c.id[a]);

  // Migration, within the MPCD step: after every step each rank's colloids carry their own
  // value. Ownership changes are counted (each rank: colloids it did not hold a step before).
  const int steps = 200;
  std::size_t wrong = 0, arrivals = 0;
  std::vector<std::uint64_t> before(c.id);
  for (int i = 0; i < steps; ++i) {
    sim.advance();
    wrong += wrong_scratch(sim.colloids(), 0, sim.colloids().size());
    for (const std::uint64_t id : sim.colloids().id)
      arrivals += std::find(before.begin(), before.end(), id) == before.end();
    before = sim.colloids().id;
  }
  EXPECT_EQ(sum(wrong), 0u) << "colloids that lost their scratch value while migrating";
  const std::size_t moved = sum(arrivals);
  if (world_size() > 1)
    ASSERT_GT(moved, 0u) << "no colloid changed rank in " << steps << " steps";
  if (world_rank() == 0)
    std::printf("%zu arrivals of colloids on another rank in %d steps\n", moved, steps);

  // Ghost copies (as the step makes them for forces): every ghost row carries its value.
  colloids::ColloidGhosts ghosts(sim.slabs(), sim.box());
  const std::size_t owned = sim.colloids().size();
  ghosts.add_for_forces(sim.colloids());
  const std::size_t copies = sim.colloids().size() - owned;
  EXPECT_EQ(sum(wrong_scratch(sim.colloids(), owned, sim.colloids().size())), 0u)
      << "ghost copies without the scratch value";
  if (world_size() > 1)
    EXPECT_GT(sum(copies), 0u) << "no ghost copy made";
  ghosts.remove(sim.colloids());
  EXPECT_EQ(sim.colloids().extra.get<double>("scratch").size(), owned);

  // Gathered (observables, checkpoints): every colloid with its value, in id order.
  const colloids::Colloids all = sim.gather_colloids();
  ASSERT_EQ(all.size(), static_cast<std::size_t>(s.colloids->count));
  EXPECT_EQ(wrong_scratch(all, 0, all.size()), 0u);

  // A checkpoint stores it as /particles/colloids/scratch/value; a restart restores it, and
  // continues bitwise as the run that goes on.
  const std::string dir = shared_tmpdir();
  ASSERT_FALSE(dir.empty());
  const std::string path = dir + "/checkpoint.h5";
  io::CheckpointInfo info;
  info.scene_text = s.text;
  info.step = sim.step();
  info.time = sim.time();
  info.seed = s.run.seed;
  info.dimensions = 2;
  info.box = sim.box().length;
  colloids::Colloids gathered = all, none;
  io::write_checkpoint(
      path, info, {mpcd::fluid_fields(sim.fluid()), mpcd::colloid_fields(gathered, none, comm)},
      comm);
  EXPECT_TRUE(io::has_species_field(path, "colloids", "scratch", comm));

  mpcd::MpcdSimulation again(s, comm, false);
  {
    const io::CheckpointInfo read = io::read_checkpoint_info(path, comm);
    again.restore(mpcd::read_fluid(path, read, comm), read.step);
    again.restore_colloids(mpcd::read_colloids(path, *s.colloids, 2, s.fluid.density, s.run.seed,
                                               comm, &sim.colloids()));
  }
  EXPECT_EQ(sum(wrong_scratch(again.colloids(), 0, again.colloids().size())), 0u)
      << "the restart lost the scratch values";
  EXPECT_EQ(sum(again.colloids().size()), static_cast<std::size_t>(s.colloids->count));
  for (int i = 0; i < 20; ++i) {
    sim.advance();
    again.advance();
  }
  EXPECT_EQ(sum(wrong_scratch(again.colloids(), 0, again.colloids().size())), 0u);
  const colloids::Colloids a = sim.gather_colloids(), b = again.gather_colloids();
  ASSERT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 2; ++k)
      differ += std::memcmp(&a.x[k][i], &b.x[k][i], sizeof(double)) != 0 ||
                std::memcmp(&a.v[k][i], &b.v[k][i], sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << "the restart did not continue bitwise";
  MPI_Barrier(comm);
  if (world_rank() == 0)
    std::filesystem::remove_all(dir);
}
