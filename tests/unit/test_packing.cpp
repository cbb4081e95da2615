// Dense packings grown from points with the spring contacts (Kanehl (thesis) §6.1): 200 bidisperse
// disks (a = 2.1 and 2.94, equal numbers, the thesis' mixture) reach area fraction 0.82 in a
// channel of width 50 with the deepest overlap below 1 % of the small radius, judged by an
// all-pairs check independent of the generator's cell list; the same seed gives the same bits; a
// fraction no spring relaxation can reach is refused with one line.
#include "narrows/colloids/packing.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/core/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

using namespace narrows;
using namespace narrows::colloids;

namespace {

// n_small + n_large disks of the thesis' radii in a channel L_x x 50 with walls.
struct Channel {
  Colloids c;
  mpcd::Box box;
};

Channel bidisperse(int n_small, int n_large, int length) {
  Channel s;
  s.box = mpcd::make_periodic_box(2, {length, 50, 1});
  s.box.walls_y = true;
  s.c.dim = 2;
  s.c.resize(static_cast<std::size_t>(n_small + n_large));
  for (std::size_t a = 0; a < s.c.size(); ++a) {
    s.c.id[a] = a;
    s.c.radius[a] = a < static_cast<std::size_t>(n_small) ? 2.1 : 2.94;
    s.c.mass[a] = 25.0 * colloid_volume(2, s.c.radius[a]);
  }
  return s;
}

double fraction(const Channel &s) {
  double area = 0.0;
  for (const double r : s.c.radius)
    area += std::numbers::pi * r * r;
  return area / (s.box.length[0] * s.box.length[1]);
}

// All pairs, minimum image along x, and both walls.
double deepest_all_pairs(const Channel &s) {
  double worst = 0.0;
  const auto &c = s.c;
  const double L = s.box.length[0];
  for (std::size_t a = 0; a < c.size(); ++a) {
    worst = std::max({worst, c.radius[a] - c.x[1][a], c.x[1][a] + c.radius[a] - s.box.length[1]});
    for (std::size_t b = a + 1; b < c.size(); ++b) {
      double dx = c.x[0][a] - c.x[0][b];
      dx -= L * std::round(dx / L);
      const double dy = c.x[1][a] - c.x[1][b];
      worst = std::max(worst, c.radius[a] + c.radius[b] - std::hypot(dx, dy));
    }
  }
  return worst;
}

} // namespace

TEST(Packing, BidisperseChannelReachesSeedFraction) {
  // 100 + 100 disks of area pi (2.1^2 + 2.94^2) each pair in 100 x 50: phi = 0.8202.
  Channel s = bidisperse(100, 100, 100);
  const double phi = fraction(s);
  ASSERT_NEAR(phi, 0.82, 0.001);
  const PackingReport r = pack_colloids(s.c, s.box, 7, "test");
  const double deepest = deepest_all_pairs(s);
  std::printf("packing: %zu disks, phi %.4f, deepest overlap %.2e of the small radius, %lld "
              "stages, %lld FIRE steps, %.2f s\n",
              s.c.size(), r.fraction, deepest / 2.1, static_cast<long long>(r.stages),
              static_cast<long long>(r.iterations), r.seconds);
  EXPECT_NEAR(r.fraction, phi, 1e-12);
  EXPECT_LT(deepest, 0.01 * 2.1);
  EXPECT_NEAR(r.max_overlap, deepest / 2.1, 1e-12); // the report measures what we measure
  for (std::size_t a = 0; a < s.c.size(); ++a) {
    EXPECT_TRUE(s.c.x[0][a] >= 0.0 && s.c.x[0][a] < 100.0);
    EXPECT_EQ(s.c.radius[a], a < 100 ? 2.1 : 2.94); // grown to the target radii
  }
}

TEST(Packing, SameSeedSameBitsOtherSeedOtherPacking) {
  Channel a = bidisperse(20, 20, 40), b = bidisperse(20, 20, 40), d = bidisperse(20, 20, 40);
  pack_colloids(a.c, a.box, 3, "test");
  pack_colloids(b.c, b.box, 3, "test");
  pack_colloids(d.c, d.box, 4, "test");
  bool differs = false;
  for (std::size_t i = 0; i < a.c.size(); ++i)
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(a.c.x[k][i], b.c.x[k][i]);
      differs = differs || a.c.x[k][i] != d.c.x[k][i];
    }
  EXPECT_TRUE(differs);
}

TEST(Packing, RefusesFractionBeyondJamming) {
  // 100 + 100 disks in 90 x 50: phi = 0.911, beyond random close packing (~0.84): the overlaps
  // cannot go; the generator stops at its iteration budget with one line.
  Channel s = bidisperse(100, 100, 90);
  PackingParams p;
  p.max_iterations = 20000;
  try {
    pack_colloids(s.c, s.box, 7, "scene.toml: colloids.packing_fraction", p);
    FAIL() << "no error";
  } catch (const Error &e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos);
    EXPECT_NE(what.find("colloids.packing_fraction"), std::string::npos) << what;
    EXPECT_NE(what.find("cannot be packed"), std::string::npos) << what;
  }
}

// After packing, each kind's ids run along x (number_along_x): the rows of a kind are in order
// of x and keep their radius, mass and id.
TEST(Packing, EachKindNumberedAlongX) {
  Channel s = bidisperse(60, 40, 60);
  const Colloids before = s.c;
  pack_colloids(s.c, s.box, 5, "test");
  int inversions = 0;
  for (std::size_t a = 0; a < s.c.size(); ++a) {
    EXPECT_EQ(s.c.radius[a], before.radius[a]);
    EXPECT_EQ(s.c.mass[a], before.mass[a]);
    EXPECT_EQ(s.c.id[a], before.id[a]);
    inversions += a > 0 && s.c.radius[a] == s.c.radius[a - 1] && s.c.x[0][a] < s.c.x[0][a - 1];
  }
  EXPECT_EQ(inversions, 0);
}

// number_along_x hands each row's whole state (position, velocity, spin, orientation) to a row
// of the same radius and mass, in order of x within each such group; radius, mass and id stay.
TEST(Packing, NumberingAlongXMovesWholeStatesWithinAKind) {
  Colloids c;
  c.dim = 2;
  c.resize(9);
  for (std::size_t a = 0; a < 9; ++a) {
    c.id[a] = 100 + a;
    c.radius[a] = a % 3 == 0 ? 1.0 : 2.0;
    c.mass[a] = a % 3 == 2 ? 7.0 : 5.0; // three groups: (1, 5), (2, 5), (2, 7)
    c.x[0][a] = std::fmod(5.0 * static_cast<double>(a), 9.0);
    c.x[1][a] = static_cast<double>(a);
    c.v[0][a] = 10.0 + static_cast<double>(a);
    c.v[1][a] = 20.0 + static_cast<double>(a);
    c.omega[2][a] = 30.0 + static_cast<double>(a);
    c.q[3][a] = 40.0 + static_cast<double>(a);
  }
  const Colloids was = c;
  number_along_x(c);
  for (std::size_t a = 0; a < 9; ++a) {
    EXPECT_EQ(c.id[a], was.id[a]);
    EXPECT_EQ(c.radius[a], was.radius[a]);
    EXPECT_EQ(c.mass[a], was.mass[a]);
    const auto from = static_cast<std::size_t>(c.x[1][a]); // the row this state came from
    EXPECT_EQ(c.radius[from], c.radius[a]);
    EXPECT_EQ(c.mass[from], c.mass[a]);
    EXPECT_EQ(c.x[0][a], was.x[0][from]);
    EXPECT_EQ(c.v[0][a], was.v[0][from]);
    EXPECT_EQ(c.v[1][a], was.v[1][from]);
    EXPECT_EQ(c.omega[2][a], was.omega[2][from]);
    EXPECT_EQ(c.q[3][a], was.q[3][from]);
    for (std::size_t b = a + 1; b < 9; ++b)
      if (c.radius[b] == c.radius[a] && c.mass[b] == c.mass[a])
        EXPECT_LT(c.x[0][a], c.x[0][b]) << a << " " << b;
  }
  std::vector<double> ys(c.x[1]);
  std::sort(ys.begin(), ys.end());
  for (std::size_t a = 0; a < 9; ++a)
    EXPECT_EQ(ys[a], static_cast<double>(a)); // every state once
}
