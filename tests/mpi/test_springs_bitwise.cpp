// Spring contacts with friction across ranks (issue 21 items 1-2): a plug of no-slip disks in a
// channel, a ring of six touching along the lower wall around the periodic x axis (so contacts
// sit across every slab edge) with three more wedged in its grooves by gravity, pushed along
// by the flow. On 2 and 3 ranks (uneven slabs of 25 cells) the colloids, the
// fluid and the contact history after 3000 steps are bitwise those of one rank, with contacts
// across a slab edge that lasted 1500 steps and more (from when the plug has settled). A checkpoint
// written on 2 ranks mid-contact continues on 1 rank bitwise; a damaged contact history in a
// checkpoint is refused with one line.
#include "narrows/engines/mpcd/colloid_checkpoint.hpp"
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "narrows/core/error.hpp"

#include "../common/state_by_id.hpp"
#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::state_by_id;
using narrows::testing::world_rank;
using narrows::testing::world_size;

scene::Scene plug_scene() {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = 2101;
  s.domain.size = {25, 12, 0};
  s.fluid.collision = scene::Collision::at_a;
  s.fluid.density = 6.0;
  s.fluid.dt = 0.1;
  s.fluid.sort_every = 7;
  // A cool fluid: at kT = 1 the thermal motion of a contact (rms sqrt(kT / kn) = 0.02) is
  // comparable to its static overlap (0.033 under M g = 83), so contacts open every ~100 steps;
  // at kT = 0.03, once the plug has settled (about 1000 steps), they last.
  s.fluid.kT = 0.03;
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {0.01, 0.0, 0.0}, 0};
  s.walls = scene::Walls{};
  scene::Colloids col;
  col.coupling = scene::ColloidCoupling::no_slip;
  col.contacts = scene::ColloidContacts::spring;
  col.spring = {2500.0, 2500.0, 0.5, 0.3, 10};
  col.radius = 2.08;
  col.placement = scene::ColloidPlacement::list;
  const double gap = 25.0 / 6.0; // six around x: 24.96 of 25 filled
  for (int i = 0; i < 6; ++i)
    col.positions.push_back({(i + 0.25) * gap, 2.081, 0.0});
  const double up = 2.081 + std::sqrt(4.16 * 4.16 - 0.25 * gap * gap) + 0.01;
  for (int i : {1, 3, 5}) // above x = 7.3, 15.6 and 24.0: across the edges of 2, 3 and 4 slabs
    col.positions.push_back({(i + 0.75) * gap, up, 0.0});
  col.count = static_cast<std::int64_t>(col.positions.size());
  // Pressed hard (M g = 83: the overlap 0.033 is 1.6 % of the radius): the upper three stay wedged
  // in their grooves for the whole run, each touching two lower ones that lie in different slabs.
  col.gravity = {0.0, -1.0, 0.0};
  s.colloids = col;
  s.text = "# spring plug\n";
  return s;
}

int slab_of(const parallel::Slabs &slabs, double x) {
  int r = 0;
  while (r + 1 < slabs.ranks() && slabs.first_column_of(r + 1) <= static_cast<int>(x))
    ++r;
  return r;
}

std::size_t colloid_differences(const colloids::Colloids &a, const colloids::Colloids &b) {
  if (a.size() != b.size())
    return std::max(a.size(), b.size()) + 1;
  std::size_t n = 0;
  const auto differ = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) != 0; };
  for (std::size_t i = 0; i < a.size(); ++i) {
    n += a.id[i] != b.id[i];
    for (int k = 0; k < a.dim; ++k)
      n += differ(a.x[k][i], b.x[k][i]) + differ(a.v[k][i], b.v[k][i]);
    for (int k = 0; k < 3; ++k)
      n += differ(a.omega[k][i], b.omega[k][i]);
    for (int k = 0; k < 4; ++k)
      n += differ(a.q[k][i], b.q[k][i]);
  }
  return n;
}

std::size_t contact_differences(const colloids::ContactHistory &a,
                                const colloids::ContactHistory &b) {
  if (a.size() != b.size())
    return std::max(a.size(), b.size()) + 1;
  std::size_t n = 0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    n += a.owner[j] != b.owner[j] || a.partner[j] != b.partner[j];
    for (int k = 0; k < a.dim; ++k)
      n += std::memcmp(&a.xi[k][j], &b.xi[k][j], sizeof(double)) != 0;
  }
  return n;
}

std::string shared_tmpdir() {
  char buf[256] = {};
  if (world_rank() == 0) {
    std::string t = (std::filesystem::temp_directory_path() / "narrows-springs-XXXXXX").string();
    std::strncpy(buf, t.c_str(), sizeof buf - 1);
    if (mkdtemp(buf) == nullptr)
      buf[0] = '\0';
  }
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

void write(const std::string &path, mpcd::MpcdSimulation &sim, colloids::ContactHistory contacts,
           MPI_Comm comm) {
  io::CheckpointInfo info;
  info.scene_text = sim.scene().text;
  info.step = sim.step();
  info.time = sim.time();
  info.seed = sim.scene().run.seed;
  info.dimensions = sim.box().dim;
  info.box = sim.box().length;
  info.walls_y = sim.box().walls_y;
  colloids::Colloids all = sim.gather_colloids(), none;
  colloids::ContactHistory no_contacts;
  io::write_checkpoint(path, info,
                       {mpcd::fluid_fields(sim.fluid()), mpcd::colloid_fields(all, none, comm),
                        mpcd::contact_fields(contacts, no_contacts, comm)},
                       comm);
}

} // namespace

TEST(SpringBitwise, PlugAcrossSlabEdgesEqualsOneRank) {
  const scene::Scene s = plug_scene();
  const int steps =
      std::getenv("NARROWS_BITWISE_STEPS") ? std::atoi(std::getenv("NARROWS_BITWISE_STEPS")) : 2000;
  mpcd::MpcdSimulation par(s, MPI_COMM_WORLD);
  // How long each contact has lasted, and whether it ever joined colloids of two slabs.
  std::map<std::pair<std::uint64_t, std::uint64_t>, int> age;
  std::map<std::pair<std::uint64_t, std::uint64_t>, bool> straddled;
  int longest_straddling = 0, longest = 0;
  for (int i = 0; i < steps; ++i) {
    par.advance();
    const auto all = par.gather_colloids();
    ASSERT_EQ(all.size(), static_cast<std::size_t>(s.colloids->count)) << "at step " << i;
    const auto h = par.gather_contacts();
    std::map<std::pair<std::uint64_t, std::uint64_t>, int> now;
    for (std::size_t j = 0; j < h.size(); ++j) {
      const auto key = std::make_pair(h.owner[j], h.partner[j]);
      now[key] = age.count(key) ? age[key] + 1 : 1;
      if (!colloids::is_wall_id(h.partner[j]) && slab_of(par.slabs(), all.x[0][h.owner[j]]) !=
                                                     slab_of(par.slabs(), all.x[0][h.partner[j]]))
        straddled[key] = true;
      if (straddled[key])
        longest_straddling = std::max(longest_straddling, now[key]);
      if (!colloids::is_wall_id(h.partner[j]))
        longest = std::max(longest, now[key]);
    }
    age = std::move(now);
  }
  const auto par_colloids = par.gather_colloids();
  const auto par_contacts = par.gather_contacts();
  const auto total = mpcd::particle_count(s);
  const auto par_fluid = state_by_id(par.fluid(), total, MPI_COMM_WORLD);
  if (world_rank() != 0)
    return;
  std::printf("%d ranks: %zu contacts at the end; the longest between two colloids lasted %d "
              "steps, the longest across a slab edge %d\n",
              world_size(), par_contacts.size(), longest, longest_straddling);
  if (world_size() > 1) {
    EXPECT_GE(longest_straddling, steps / 2) << "no contact across a slab edge lasted";
  }
  mpcd::MpcdSimulation ser(s, MPI_COMM_SELF);
  for (int i = 0; i < steps; ++i)
    ser.advance();
  EXPECT_EQ(colloid_differences(par_colloids, ser.gather_colloids()), 0u);
  EXPECT_EQ(contact_differences(par_contacts, ser.gather_contacts()), 0u);
  const auto ser_fluid = state_by_id(ser.fluid(), total, MPI_COMM_SELF);
  std::size_t differ = 0;
  for (std::size_t j = 0; j < ser_fluid.size(); ++j)
    differ += std::memcmp(&ser_fluid[j], &par_fluid[j], sizeof(double)) != 0;
  EXPECT_EQ(differ, 0u) << "fluid numbers differ after " << steps << " steps";
}

TEST(SpringBitwise, RestartMidContactOnOneRankContinuesBitwise) {
  const scene::Scene s = plug_scene();
  constexpr int half = 150;
  const std::string dir = shared_tmpdir();
  ASSERT_FALSE(dir.empty());
  const std::string path = dir + "/springs.h5";
  // Straight, 2 half-runs on WORLD.
  mpcd::MpcdSimulation straight(s, MPI_COMM_WORLD);
  for (int i = 0; i < half; ++i)
    straight.advance();
  const auto at_checkpoint = straight.gather_contacts();
  write(path, straight, at_checkpoint, MPI_COMM_WORLD);
  for (int i = 0; i < half; ++i)
    straight.advance();
  const auto ref_colloids = straight.gather_colloids();
  const auto ref_contacts = straight.gather_contacts();
  const auto total = mpcd::particle_count(s);
  const auto ref_fluid = state_by_id(straight.fluid(), total, MPI_COMM_WORLD);
  if (world_rank() == 0) {
    std::size_t pairs = 0;
    for (std::size_t j = 0; j < at_checkpoint.size(); ++j)
      pairs += !colloids::is_wall_id(at_checkpoint.partner[j]);
    EXPECT_GT(pairs, 5u) << "the checkpoint should be mid-contact";
    // Continued on one rank from the checkpoint of WORLD.
    const auto info = io::read_checkpoint_info(path, MPI_COMM_SELF);
    mpcd::MpcdSimulation sim(s, MPI_COMM_SELF, false);
    sim.restore(mpcd::read_fluid(path, info, MPI_COMM_SELF), info.step);
    sim.restore_colloids(
        mpcd::read_colloids(path, *s.colloids, 2, s.fluid.density, s.run.seed, MPI_COMM_SELF));
    sim.restore_contacts(mpcd::read_contacts(path, s.colloids->count, 2, true, MPI_COMM_SELF));
    EXPECT_EQ(contact_differences(sim.gather_contacts(), at_checkpoint), 0u);
    for (int i = 0; i < half; ++i)
      sim.advance();
    EXPECT_EQ(colloid_differences(sim.gather_colloids(), ref_colloids), 0u);
    EXPECT_EQ(contact_differences(sim.gather_contacts(), ref_contacts), 0u);
    const auto fluid = state_by_id(sim.fluid(), total, MPI_COMM_SELF);
    std::size_t differ = 0;
    for (std::size_t j = 0; j < fluid.size(); ++j)
      differ += std::memcmp(&fluid[j], &ref_fluid[j], sizeof(double)) != 0;
    EXPECT_EQ(differ, 0u) << "2 ranks -> 1 rank";

    // Damaged histories are refused with one line naming the dataset.
    struct Damage {
      const char *what, *expect;
      void (*apply)(colloids::ContactHistory &);
    };
    const Damage damages[] = {{"partner below owner", "partner_id",
                               [](colloids::ContactHistory &h) { h.partner[0] = h.owner[0]; }},
                              {"owner beyond the colloids", "owner_id",
                               [](colloids::ContactHistory &h) { h.owner[h.size() - 1] = 1000; }},
                              {"not finite", "tangential_displacement",
                               [](colloids::ContactHistory &h) {
                                 h.xi[0][0] = std::numeric_limits<double>::quiet_NaN();
                               }},
                              {"twice", "twice", [](colloids::ContactHistory &h) {
                                 h.owner[1] = h.owner[0];
                                 h.partner[1] = h.partner[0];
                               }}};
    for (const auto &d : damages) {
      colloids::ContactHistory bad = at_checkpoint;
      d.apply(bad);
      const std::string damaged = dir + "/damaged.h5";
      write(damaged, sim, bad, MPI_COMM_SELF);
      try {
        mpcd::read_contacts(damaged, s.colloids->count, 2, true, MPI_COMM_SELF);
        ADD_FAILURE() << d.what << ": not refused";
      } catch (const Error &e) {
        EXPECT_EQ(e.code(), ExitCode::bad_input);
        const std::string m = e.what();
        EXPECT_NE(m.find(d.expect), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        std::printf("refused (%s): %s\n", d.what, e.what());
      }
    }
    std::filesystem::remove_all(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}
