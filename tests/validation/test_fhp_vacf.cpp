// Tagged-particle VACF of the FHP models by moment propagation on the lattice slabs
// (van der Hoef & Frenkel §3; issue 6 point 3): the slab implementation against the library kernel,
// the one-step VACF against eq 19 with collisions on, and the 2D long-time tail t^-1.
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/engines/lgca/fhp_tagged.hpp"
#include "narrows/engines/lgca/moment_propagation.hpp"
#include "narrows/engines/lgca/vacf_theory.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace narrows::lgca;

namespace {

FhpParams params(FhpModel m, int x, int y, std::uint64_t seed) {
  FhpParams p;
  p.model = m;
  p.size_x = x;
  p.size_y = y;
  p.seed = seed;
  return p;
}

// The whole lattice of one rank as the library indexes it (site y * size_x + x).
std::vector<std::uint8_t> occupation(const FhpLattice &l) {
  std::vector<std::uint8_t> occ;
  for (int y = 0; y < l.size_y(); ++y)
    for (int x = 0; x < l.size_x(); ++x)
      occ.push_back(l.row(y)[x]);
  return occ;
}

} // namespace

// Pull on slabs (fhp_tagged) and push with a neighbour table (moment_propagation) are the same
// eq 11 summed in another order: equal to rounding.
TEST(FhpVacf, SlabKernelEqualsLibraryKernel) {
  // FHP-II: C(0) (moving particles / N) changes from curve to curve, so one curve is compared;
  // FHP-I: C(0) = 1, five successive curves (the restart of an origin) are compared.
  for (const auto m : {FhpModel::fhp_i, FhpModel::fhp_ii}) {
    const int max_lag = m == FhpModel::fhp_i ? 12 : 60, curves = m == FhpModel::fhp_i ? 5 : 1;
    FhpLattice l(params(m, 24, 16, 5), MPI_COMM_SELF);
    l.initialise(0.35, 0.05);
    FhpTagged mine(l, max_lag);
    MomentPropagation lib(triangular_links(links(m) == 7), triangular_neighbours(24, 16, links(m)),
                          max_lag);
    mine.feed(l);
    lib.feed(occupation(l));
    for (int i = 0; i < max_lag * curves; ++i) {
      l.step();
      mine.feed(l);
      lib.feed(occupation(l));
    }
    ASSERT_EQ(mine.curves(), curves);
    ASSERT_EQ(lib.curves(), curves);
    const auto z = mine.mean(), c = lib.mean();
    for (int t = 0; t <= max_lag; ++t)
      EXPECT_NEAR(z[t], c[t] / c[0], 1e-12) << to_string(m) << " lag " << t;
  }
}

// Eq 19 (equal split over the outgoing particles, any collision rule) with the collisions of
// each model on: 1-step curves at every step of an equilibrium run. Eq 19 is taken at the
// density of the lattice, N / (b sites): N is conserved, and the initial draw misses d by
// sqrt(d (1 - d) / (b sites)) = 6e-4 at d = 0.2, which moves eq 19 by 1e-3 (the first
// version of this test compared with eq 19 at the nominal d and was 7 sigma off for FHP-I at
// d = 0.2). The standard error over time origins is below 2e-4 (checked), so the 1e-3 bound
// is at least 5 sigma, and a wrong split (e.g. over all links) misses it by far.
TEST(FhpVacf, OneStepEqualsEq19) {
  for (const auto m : {FhpModel::fhp_i, FhpModel::fhp_iii}) {
    for (const double d : {0.2, 0.5}) {
      FhpLattice l(params(m, 256, 256, 17), MPI_COMM_WORLD);
      l.initialise(d, 0.0);
      FhpTagged tagged(l, 1);
      tagged.feed(l);
      for (int i = 0; i < 100; ++i) {
        l.step();
        tagged.feed(l);
      }
      int rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (rank != 0)
        continue;
      const double z = tagged.mean()[1], e = tagged.error()[1];
      const double dl = tagged.particles() / (links(m) * 256.0 * 256.0);
      const double eq19 = theory::one_step_vacf_closed_form(links(m), dl);
      std::printf("%s d = %.2f (lattice %.6f): Z(1) = %.6f +- %.6f, eq 19 %.6f, difference "
                  "%.2e\n",
                  to_string(m), d, dl, z, e, eq19, z - eq19);
      EXPECT_LT(e, 2e-4);
      EXPECT_NEAR(z, eq19, 1e-3) << to_string(m) << " d = " << d;
    }
  }
}

namespace {

// Least-squares slope of ln z against ln t over lags [t1, t2] (z > 0 required).
double log_slope(const std::vector<double> &z, int t1, int t2) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (int t = t1; t <= t2; ++t) {
    const double x = std::log(static_cast<double>(t)), y = std::log(z[t]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace

// The 2D long-time tail (van der Hoef & Frenkel §3.5, fig 2a): Z(t) + (1 - d)/N (eq 22) ~ t^-a
// with a -> 1. FHP-III, d = 0.3, 256 x 256 sites, 4 blocks of 50 successive curves of 200 lags
// (40000 steps, about 30 s on one core). Window [50, 200]: from 50 mean free times (t0 = 0.93, the
// Boltzmann part Z(1)^t is e^-50 there) to below the time sound needs to cross the box
// (L_y sqrt 2 = 313 steps); the diffusive cut-off of the periodic box ((L / 2 pi)^2 / nu ~ 1e4
// steps) is far. The effective exponent still grows slowly towards 1 (the run that set this test
// up: lags 20..100 a = 0.90 +- 0.013, 50..200 a = 0.97 +- 0.03; the plot tool's fit over 200 curves
// of one run gives 0.974 for 50..200). The error is the spread of the 4 blocks (lags of one
// curve are strongly correlated, so a fit weighted per lag would understate it ten-fold).
// The test asserts |a - 1| < 0.12 (4 block sigma) with the block error below 0.05: an
// exponential decay, a t^-3/2 (3D) tail or a lost weight would all fail.
TEST(FhpVacf, LongTimeTailApproachesOneOverT) {
  FhpLattice l(params(FhpModel::fhp_iii, 256, 256, 29), MPI_COMM_WORLD);
  l.initialise(0.3, 0.0);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::vector<double> late, early;
  for (int block = 0; block < 4; ++block) {
    FhpTagged tagged(l, 200);
    tagged.feed(l);
    while (tagged.curves() < 50) {
      l.step();
      tagged.feed(l);
    }
    if (rank != 0)
      continue;
    auto z = tagged.mean();
    const double correction = theory::finite_size_correction(0.3, tagged.particles());
    for (double &v : z)
      v += correction;
    for (int t = 20; t <= 200; ++t)
      ASSERT_GT(z[t], 0.0) << "lag " << t;
    late.push_back(log_slope(z, 50, 200));
    early.push_back(log_slope(z, 20, 100));
  }
  if (rank != 0)
    return;
  const auto mean_err = [](const std::vector<double> &a) {
    double m = 0.0, v = 0.0;
    for (double x : a)
      m += x / a.size();
    for (double x : a)
      v += (x - m) * (x - m) / (a.size() - 1);
    return std::pair{m, std::sqrt(v / a.size())};
  };
  const auto [a, da] = mean_err(late);
  const auto [b, db] = mean_err(early);
  std::printf("FHP-III d = 0.3, 256 x 256: Z ~ t^-a, a = %.4f +- %.4f (lags 50..200), "
              "%.4f +- %.4f (lags 20..100), 4 blocks of 50 curves\n",
              -a, da, -b, db);
  EXPECT_LT(da, 0.05);
  EXPECT_NEAR(-a, 1.0, 0.12);
}
