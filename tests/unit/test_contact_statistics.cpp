// The contact network and its statistics (observable contact_statistics, Kanehl (thesis) fig
// 6.2a): in a random dense packing of bidisperse disks between walls, shaken so that contacts
// stick and slide, the network has exactly the contacts the spring kernel counted in its last
// update, and as sliding exactly those the kernel cut back to the Coulomb cap; its overlaps are
// those of the geometry; the histogram puts each overlap delta / min(r_i, r_j) in its bin (walls
// apart) and the coordination counts partners per kind.
#include "narrows/analysis/contact_statistics.hpp"
#include "narrows/colloids/contact_network.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/springs.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace narrows;
using namespace narrows::colloids;

namespace {

// n disks of radii 1 and 1.4 (alternating) at random in an L x L box with walls at y = 0, L,
// overlapping here and there, with random velocities and spins.
Colloids shaken(std::size_t n, double L, std::uint32_t seed) {
  Colloids c;
  c.dim = 2;
  c.resize(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t a = 0; a < n; ++a) {
    c.id[a] = a;
    c.radius[a] = a % 2 == 0 ? 1.0 : 1.4;
    c.mass[a] = 25.0 * colloid_volume(2, c.radius[a]);
    c.x[0][a] = L * u(rng);
    c.x[1][a] = 0.8 + (L - 1.6) * u(rng); // (some over a wall)
    c.v[0][a] = 2.0 * u(rng) - 1.0;
    c.v[1][a] = 2.0 * u(rng) - 1.0;
    c.omega[2][a] = 2.0 * u(rng) - 1.0;
  }
  return c;
}

} // namespace

TEST(ContactNetwork, SameContactsAndSlidingAsTheKernel) {
  const double L = 20.0;
  const Colloids c = shaken(160, L, 31); // area fraction ~0.5: many contacts
  mpcd::Box box = mpcd::make_periodic_box(2, {20, 20, 1});
  box.walls_y = true;
  SpringParams p;
  p.mu_cc = 0.5;
  p.mu_cw = 0.3;
  SpringContacts springs(p, box);
  ContactHistory h;
  h.dim = 2;
  // Springs grow over a few updates (tangential speeds ~1, steps 0.01: |xi| up to ~0.03 while the
  // caps mu delta run from 0 to ~0.2), so some contacts slide and some stick.
  std::uint64_t updates = 0, sliding = 0;
  for (int k = 0; k < 3; ++k) {
    updates = springs.contact_updates();
    sliding = springs.sliding_updates();
    springs.compute(c, c.size(), h, 0.01);
  }
  updates = springs.contact_updates() - updates; // the last update's
  sliding = springs.sliding_updates() - sliding;
  const ContactNetwork net = contact_network(c, h, box, p);
  ASSERT_GT(updates, 50u);
  ASSERT_GT(sliding, 0u);
  ASSERT_LT(sliding, updates);
  EXPECT_EQ(net.size(), updates);
  std::uint64_t slid = 0, walls = 0;
  for (std::size_t j = 0; j < net.size(); ++j) {
    slid += net.sliding[j];
    walls += net.is_wall(j);
  }
  EXPECT_EQ(slid, sliding);
  EXPECT_GT(walls, 0u);

  // Every overlap from the geometry, and every pair that overlaps is in the network once.
  std::size_t pairs = 0;
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      const double dx = minimum_image(c.x[0][b] - c.x[0][a], L), dy = c.x[1][b] - c.x[1][a];
      const double delta = c.radius[a] + c.radius[b] - std::sqrt(dx * dx + dy * dy);
      if (delta <= 0.0)
        continue;
      ++pairs;
      std::size_t found = 0;
      for (std::size_t j = 0; j < net.size(); ++j)
        if (net.owner[j] == a && net.partner[j] == b) {
          ++found;
          EXPECT_NEAR(net.overlap[j], delta, 1e-12);
          EXPECT_EQ(net.scale[j], std::min(c.radius[a], c.radius[b]));
          EXPECT_NEAR(net.normal[j], p.kn * delta, 1e-9);
        }
      EXPECT_EQ(found, 1u) << a << " " << b;
    }
  EXPECT_EQ(pairs + walls, net.size());

  // The statistics of that network.
  std::vector<std::size_t> kinds(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    kinds[a] = a % 2;
  const analysis::ContactStatistics st = analysis::contact_statistics(net, c.id, kinds, 2);
  using B = analysis::ContactStatistics;
  std::array<std::vector<double>, 2> want;
  want[0].assign(B::bins, 0.0);
  want[1].assign(B::bins, 0.0);
  std::array<double, 2> beyond{0.0, 0.0}, slides{0.0, 0.0};
  std::vector<double> partners(c.size(), 0.0);
  for (std::size_t j = 0; j < net.size(); ++j) {
    const int w = net.is_wall(j);
    const double x = net.overlap[j] / net.scale[j];
    const auto b = static_cast<std::size_t>(x / 0.002);
    if (x < 0.2)
      want[w][b] += 1.0;
    else
      beyond[w] += 1.0;
    slides[w] += net.sliding[j];
    if (!w) {
      partners[net.owner[j]] += 1.0;
      partners[net.partner[j]] += 1.0;
    }
  }
  for (int w = 0; w < 2; ++w) {
    EXPECT_EQ(st.histogram[w], want[w]) << w;
    EXPECT_EQ(st.beyond[w], beyond[w]);
    EXPECT_DOUBLE_EQ(st.sliding[w] * st.contacts[w], slides[w]);
  }
  EXPECT_EQ(st.contacts[0], static_cast<double>(pairs));
  EXPECT_EQ(st.contacts[1], static_cast<double>(walls));
  for (std::size_t k = 0; k < 2; ++k) {
    double sum = 0.0;
    for (std::size_t a = k; a < c.size(); a += 2)
      sum += partners[a];
    EXPECT_DOUBLE_EQ(st.coordination[k], sum / 80.0);
  }
  EXPECT_DOUBLE_EQ(B::bin_centres().front(), 0.001);
  EXPECT_DOUBLE_EQ(B::bin_centres().back(), 0.199);
}

TEST(ContactNetwork, NeverSlidesWithInfiniteFriction) {
  const Colloids c = shaken(160, 20.0, 31);
  mpcd::Box box = mpcd::make_periodic_box(2, {20, 20, 1});
  box.walls_y = true;
  SpringParams p;
  p.mu_cc = p.mu_cw = never_slides;
  SpringContacts springs(p, box);
  ContactHistory h;
  h.dim = 2;
  for (int k = 0; k < 3; ++k)
    springs.compute(c, c.size(), h, 0.01);
  const ContactNetwork net = contact_network(c, h, box, p);
  ASSERT_GT(net.size(), 50u);
  for (std::size_t j = 0; j < net.size(); ++j)
    EXPECT_EQ(net.sliding[j], 0);
}
