// Moment propagation: the neighbour maps (ring, triangular) are consistent, eq 11 conserves the
// total tagged weight in 1D and 2D, the lag-0 value is <v^2>, and the one-step VACF of the
// theory (eq 18 by enumeration) agrees with eq 19 where eq 19 applies.
#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/lgca/dhumieres_1d.hpp"
#include "narrows/engines/lgca/moment_propagation.hpp"
#include "narrows/engines/lgca/vacf_theory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::lgca;

// Position of a triangular-lattice site, unwrapped: (x + (y mod 2)/2, y sqrt(3)/2).
std::array<double, 2> position(std::int64_t nx, std::int64_t site) {
  const std::int64_t x = site % nx, y = site / nx;
  return {x + 0.5 * static_cast<double>(y & 1), y * std::sqrt(3.0) / 2.0};
}

TEST(MomentPropagation, TriangularNeighboursInvertAndStepByTheLinkVelocity) {
  const std::int64_t nx = 6, ny = 4;
  const auto nb = triangular_neighbours(nx, ny, 7);
  const auto c = triangular_links(true);
  const double lx = nx, ly = ny * std::sqrt(3.0) / 2.0;
  for (std::int64_t r = 0; r < nx * ny; ++r) {
    EXPECT_EQ(nb[r * 7 + 6], r); // rest particle stays
    for (int i = 0; i < 6; ++i) {
      const std::int64_t to = nb[r * 7 + i];
      EXPECT_EQ(nb[to * 7 + (i + 3) % 6], r) << "site " << r << " link " << i;
      // the displacement is c_i modulo the periodic box
      const auto p = position(nx, r), q = position(nx, to);
      double dx = q[0] - p[0] - c.cx[i], dy = q[1] - p[1] - c.cy[i];
      dx -= lx * std::round(dx / lx);
      dy -= ly * std::round(dy / ly);
      EXPECT_NEAR(dx, 0.0, 1e-12) << "site " << r << " link " << i;
      EXPECT_NEAR(dy, 0.0, 1e-12) << "site " << r << " link " << i;
    }
  }
  EXPECT_THROW(triangular_neighbours(6, 5, 7), Error); // odd number of rows cannot wrap
}

TEST(MomentPropagation, TriangularLinksSumToZeroAndHaveUnitSpeed) {
  const auto c = triangular_links(false);
  double sx = 0, sy = 0;
  for (int i = 0; i < 6; ++i) {
    sx += c.cx[i];
    sy += c.cy[i];
    EXPECT_NEAR(c.cx[i] * c.cx[i] + c.cy[i] * c.cy[i], 1.0, 1e-15);
  }
  EXPECT_EQ(sx, 0.0);
  EXPECT_EQ(sy, 0.0);
}

TEST(MomentPropagation, RingNeighboursInvertForOppositeLinks) {
  const auto nb = dhumieres::neighbours(11);
  const int opposite[5] = {1, 0, 3, 2, 4};
  for (std::int64_t r = 0; r < 11; ++r)
    for (int i = 0; i < 5; ++i)
      EXPECT_EQ(nb[nb[r * 5 + i] * 5 + opposite[i]], r);
}

// Random occupations with at least one particle on every site (the weight can never reach an
// empty site), a new one each step: the total weight of each component is unchanged.
std::vector<std::uint8_t> random_occupation(std::int64_t sites, int links, std::uint64_t step) {
  std::vector<std::uint8_t> occ(static_cast<std::size_t>(sites));
  for (std::int64_t r = 0; r < sites; ++r) {
    const auto w = rng::draw(1, rng::Purpose::test, step, r);
    auto s = static_cast<std::uint8_t>(w[0] & ((1u << links) - 1));
    occ[r] = s ? s : static_cast<std::uint8_t>(1u << (w[1] % links));
  }
  return occ;
}

void check_conservation(const Links &links, const NeighbourTable &nb, std::int64_t sites) {
  const int b = links.count(), dims = links.dims();
  std::vector<double> a(static_cast<std::size_t>(sites * dims)), next(a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    a[k] = rng::open01(rng::draw(2, rng::Purpose::test, 0, k)[0]) - 0.3;
  std::vector<double> total(dims, 0.0);
  for (std::size_t k = 0; k < a.size(); ++k)
    total[k % dims] += a[k];
  for (std::uint64_t step = 1; step <= 40; ++step) {
    propagate_tagged(random_occupation(sites, b, step), nb, b, dims, a, next);
    std::swap(a, next);
    for (int k = 0; k < dims; ++k) {
      double t = 0.0;
      for (std::int64_t r = 0; r < sites; ++r)
        t += a[r * dims + k];
      ASSERT_NEAR(t, total[k], 1e-10) << "component " << k << " step " << step;
    }
  }
}

TEST(MomentPropagation, ConservesTotalTaggedWeight1d) {
  check_conservation(dhumieres::link_velocities(), dhumieres::neighbours(50), 50);
}

TEST(MomentPropagation, ConservesTotalTaggedWeight2d) {
  check_conservation(triangular_links(true), triangular_neighbours(8, 6, 7), 48);
  check_conservation(triangular_links(false), triangular_neighbours(8, 6, 6), 48);
}

TEST(MomentPropagation, WeightAtAnEmptySiteIsAnInvariantError) {
  const auto nb = dhumieres::neighbours(5);
  std::vector<std::uint8_t> occ = {1, 0, 1, 1, 1};
  std::vector<double> a = {0, 0.5, 0, 0, 0}, next(5);
  EXPECT_THROW(propagate_tagged(occ, nb, 5, 1, a, next), Error);
}

// Lag 0 is the mean square velocity of the particles of the start state; a single particle on
// an otherwise empty ring keeps its velocity, so C(t) = c^2 for every lag.
TEST(MomentPropagation, LagZeroAndAFreeParticle) {
  const std::int64_t L = 9;
  MomentPropagation mp(dhumieres::link_velocities(), dhumieres::neighbours(L), 4);
  std::vector<std::uint8_t> occ(L, 0);
  occ[2] = 0b01000; // velocity -2
  std::vector<std::uint8_t> next(L);
  mp.feed(occ);
  for (int t = 1; t <= 4; ++t) {
    dhumieres::propagate(occ, next);
    std::swap(occ, next);
    mp.feed(occ);
  }
  ASSERT_EQ(mp.curves(), 1);
  for (double c : mp.mean())
    EXPECT_DOUBLE_EQ(c, 4.0);
}

TEST(VacfTheory, EnumeratedOneStepVacfMatchesErnstNaitoh) {
  for (double d : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    EXPECT_NEAR(theory::one_step_vacf(triangular_links(false), d),
                theory::one_step_vacf_closed_form(6, d), 1e-14)
        << "d = " << d;
    Links pm1{{1.0, -1.0}, {}};
    EXPECT_NEAR(theory::one_step_vacf(pm1, d), 1.0 - d, 1e-14); // eq 19 with b = 2
  }
}

TEST(VacfTheory, DhumieresOneStepVacfAndDerivedCoefficients) {
  const auto links = dhumieres::link_velocities();
  EXPECT_DOUBLE_EQ(theory::mean_square_velocity(links), 2.0);
  const double z1 = theory::one_step_vacf(links, 0.7);
  EXPECT_GT(z1, 0.0);
  EXPECT_LT(z1, 1.0);
  // eq 19 needs only sum_k c_k = 0 (then sum_{k != i} c_i.c_k = -c_i^2 for every link i), so
  // it holds with the rest particle counted in b and with unequal speeds
  EXPECT_NEAR(z1, theory::one_step_vacf_closed_form(5, 0.7), 1e-14);
  EXPECT_NEAR(z1, 0.3 * (1.0 - std::pow(0.3, 4)) / (0.7 * 4), 1e-14);
  EXPECT_DOUBLE_EQ(theory::boltzmann_diffusion(2.0, z1), 2.0 * (0.5 + z1 / (1.0 - z1)));
  EXPECT_DOUBLE_EQ(theory::mean_free_time(z1), -1.0 / std::log(z1));
  EXPECT_DOUBLE_EQ(theory::finite_size_correction(0.7, 1750.0), 0.3 / 1750.0);
  EXPECT_DOUBLE_EQ(theory::intermediate_plateau(0.7, 1750.0, 0.0), -0.3 / 1750.0);
  EXPECT_NEAR(theory::intermediate_plateau(0.7, 1750.0, 0.3), 0.0, 1e-18);
}

} // namespace

namespace {

// Free streaming on a triangular lattice with independent occupations d: any collision keeps
// u(s), so the one-step VACF of moment propagation is eq 18/19 even without collisions. Checks
// the 2D path (both velocity components, neighbour table, lag-0 normalisation) end to end; the
// error is the spread over independent configurations.
TEST(MomentPropagation, TriangularOneStepVacfMatchesEq19) {
  const std::int64_t nx = 128, ny = 128, sites = nx * ny;
  const double d = 0.3;
  const auto links = triangular_links(false);
  const auto nb = triangular_neighbours(nx, ny, 6);
  std::vector<std::uint8_t> occ(sites), next(sites);
  const auto threshold = static_cast<std::uint32_t>(d * 4294967296.0);
  const int configurations = 40;
  double sum = 0.0, sq = 0.0;
  for (int k = 0; k < configurations; ++k) {
    for (std::int64_t r = 0; r < sites; ++r) {
      const auto w0 = rng::draw(3, rng::Purpose::test, 2 * k, r);
      const auto w1 = rng::draw(3, rng::Purpose::test, 2 * k + 1, r);
      std::uint8_t s = 0;
      for (int i = 0; i < 6; ++i)
        if ((i < 4 ? w0[i] : w1[i - 4]) < threshold)
          s = static_cast<std::uint8_t>(s | (1u << i));
      occ[r] = s;
    }
    for (auto &n : next)
      n = 0;
    for (std::int64_t r = 0; r < sites; ++r)
      for (int i = 0; i < 6; ++i) {
        const auto to = nb[r * 6 + i];
        next[to] = static_cast<std::uint8_t>(next[to] | (occ[r] & (1u << i)));
      }
    MomentPropagation mp(links, nb, 1);
    mp.feed(occ);
    mp.feed(next);
    ASSERT_EQ(mp.curves(), 1);
    EXPECT_NEAR(mp.mean()[0], 1.0, 1e-12); // <|c|^2> = 1 on every particle
    const double z1 = mp.mean()[1] / mp.mean()[0];
    sum += z1;
    sq += z1 * z1;
  }
  const double mean = sum / configurations;
  const double err = std::sqrt((sq / configurations - mean * mean) / (configurations - 1));
  const double theory = theory::one_step_vacf_closed_form(6, d);
  EXPECT_NEAR(mean, theory, 4.0 * err) << "error " << err;
  EXPECT_LT(err, 2e-3);
}

} // namespace
