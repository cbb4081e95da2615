// The contact network and its statistics (observable contact_statistics, trajectory /contacts) on
// several ranks (issue 31 item 2): a dense bidisperse packing of no-slip disks with spring
// contacts in a driven channel, sampled every 50 steps; the network (ids, overlaps, forces,
// sliding flags) and the statistics (overlap histograms, sliding fractions, coordination per
// kind) made from the gathered colloids and contacts are bitwise those of one rank, with
// contacts straddling slab edges (each held once, by the rank of its owner colloid).
#include "narrows/analysis/contact_statistics.hpp"
#include "narrows/colloids/contact_network.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/scene/parse.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstring>
#include <vector>

using namespace narrows;

namespace {

using narrows::testing::world_rank;
using narrows::testing::world_size;

// A short Table 6.1 channel (Kanehl (thesis) ch.6) with fewer fluid particles: packed to 0.72.
scene::Scene dense_scene() {
  return scene::parse_scene(R"([run]
dimensions = 2
seed = 3101
steps = 200
[domain]
size = [48.0, 16.0]
[fluid]
collision = "at+a"
density = 6
dt = 0.02
[body_force]
value = [0.05, 0.0]
acts_on = "fluid+colloids"
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
placement = "packing"
packing_fraction = 0.72
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 1.0
mu_cw = 1.0
substeps = 10
[[colloids.kind]]
radius = 1.5
count = 1
[[colloids.kind]]
radius = 2.1
count = 1
)",
                            "dense_channel.toml");
}

struct Sample {
  colloids::ContactNetwork net;
  analysis::ContactStatistics stats;
  std::size_t straddling = 0; // colloid pairs whose centres lie in different slabs
};

Sample sample(const mpcd::MpcdSimulation &sim) {
  const colloids::Colloids c = sim.gather_colloids();
  const colloids::ContactHistory h = sim.gather_contacts();
  Sample out;
  out.net = colloids::contact_network(c, h, sim.box(), sim.plan().no_slip_params.spring);
  const auto &spec = *sim.scene().colloids;
  std::vector<std::size_t> kinds(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    kinds[a] = spec.kind_of(c.id[a]);
  out.stats = analysis::contact_statistics(out.net, c.id, kinds, spec.kind_count());
  const auto slab = [&](double x) {
    int r = 0;
    while (r + 1 < sim.slabs().ranks() && sim.slabs().first_column_of(r + 1) <= static_cast<int>(x))
      ++r;
    return r;
  };
  for (std::size_t j = 0; j < out.net.size(); ++j)
    if (!out.net.is_wall(j))
      out.straddling += slab(c.x[0][out.net.owner[j]]) != slab(c.x[0][out.net.partner[j]]);
  return out;
}

template <class T> bool same_bytes(const std::vector<T> &a, const std::vector<T> &b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

std::size_t differences(const Sample &a, const Sample &b) {
  const auto &x = a.net, &y = b.net;
  std::size_t n = !same_bytes(x.owner, y.owner) + !same_bytes(x.partner, y.partner) +
                  !same_bytes(x.overlap, y.overlap) + !same_bytes(x.scale, y.scale) +
                  !same_bytes(x.normal, y.normal) + !same_bytes(x.tangential, y.tangential) +
                  !same_bytes(x.sliding, y.sliding);
  for (int w = 0; w < 2; ++w) {
    n += !same_bytes(a.stats.histogram[w], b.stats.histogram[w]);
    n += std::memcmp(&a.stats.contacts[w], &b.stats.contacts[w], sizeof(double)) != 0;
    n += std::memcmp(&a.stats.beyond[w], &b.stats.beyond[w], sizeof(double)) != 0;
    n += std::memcmp(&a.stats.sliding[w], &b.stats.sliding[w], sizeof(double)) != 0;
  }
  return n + !same_bytes(a.stats.coordination, b.stats.coordination);
}

} // namespace

TEST(ContactStatisticsBitwise, DenseChannelEqualsOneRank) {
  const scene::Scene s = dense_scene();
  constexpr int steps = 200, every = 50;
  mpcd::MpcdSimulation par(s, MPI_COMM_WORLD);
  std::vector<Sample> samples;
  for (int i = 1; i <= steps; ++i) {
    par.advance();
    if (i % every == 0)
      samples.push_back(sample(par)); // collective
  }
  if (world_rank() != 0)
    return;
  mpcd::MpcdSimulation ser(s, MPI_COMM_SELF);
  std::size_t straddling = 0, contacts = 0;
  for (int i = 1; i <= steps; ++i) {
    ser.advance();
    if (i % every == 0) {
      const Sample &p = samples[static_cast<std::size_t>(i / every - 1)];
      EXPECT_EQ(differences(p, sample(ser)), 0u)
          << "at step " << i << " on " << world_size() << " ranks";
      straddling += p.straddling;
      contacts += p.net.size();
    }
  }
  std::printf("%d ranks: %zu contacts in %d samples, %zu of them between colloids of two slabs\n",
              world_size(), contacts, steps / every, straddling);
  EXPECT_GT(contacts, 4u * 25u); // (about 45 per sample among 53 disks: enough to compare)
  if (world_size() > 1) {
    EXPECT_GT(straddling, 0u) << "no contact across a slab edge: little compared";
  }
}
