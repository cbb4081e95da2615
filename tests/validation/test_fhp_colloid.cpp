// The Ladd-Frenkel colloid in the FHP lattice gas (van der Hoef & Frenkel §4.2-4.3, issue 6
// point 4), held and moving: total momentum of fluid + colloid conserved exactly, the
// moving-boundary rule handing the colloid's momentum to the fluid, the moving disc's geometry and
// drift.
#include "narrows/core/error.hpp"
#include "narrows/engines/lgca/colloid_correlations.hpp"
#include "narrows/engines/lgca/fhp_colloid.hpp"
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/engines/lgca/fhp_observables.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace narrows::lgca;

namespace {

FhpParams params() {
  FhpParams p;
  p.model = FhpModel::fhp_saturated;
  p.size_x = 64;
  p.size_y = 64;
  p.seed = 21;
  return p;
}

} // namespace

// Momentum in integer units: every reflection moves exactly 2 c_k between fluid and colloid,
// collisions conserve the fluid's own. Checked at every step of 3000, with a moving, rotating
// disc (both crossing and reflection happen) and with a held one at rest.
TEST(FhpColloid, TotalMomentumConservedExactly) {
  for (const double v : {0.0, 0.08}) {
    FhpLattice l(params(), MPI_COMM_SELF);
    l.initialise(0.5, 0.0);
    ColloidParams cp;
    cp.x = 30.3;
    cp.y = 27.1;
    cp.radius = 2.5;
    cp.mass = 40.0;
    cp.vx = v;
    cp.vy = -0.5 * v;
    cp.seed_for_rules = 21;
    FhpColloid c(cp, l);
    // sites within R: about the disc area over the area of a site, pi R^2 / (sqrt(3) / 2) = 22.7
    EXPECT_NEAR(c.inside_sites(), 22.7, 3.0);
    EXPECT_GT(c.boundary_links(), 20);
    const auto f0 = fluid_momentum(l);
    const auto c0 = c.momentum();
    std::int64_t changes = 0;
    for (int i = 0; i < 3000; ++i) {
      const auto before = c.momentum();
      c.apply(l);
      l.step();
      changes += c.momentum() != before;
      const auto f = fluid_momentum(l);
      const auto m = c.momentum();
      ASSERT_EQ(f[0] + m[0], f0[0] + c0[0]) << "step " << i;
      ASSERT_EQ(f[1] + m[1], f0[1] + c0[1]) << "step " << i;
    }
    EXPECT_GT(changes, 2000); // the colloid is hit nearly every step: not a vacuous check
    std::printf("v0 = %.2f: colloid momentum changed in %lld of 3000 steps, final (%lld, %lld) "
                "units, omega %.3g\n",
                v, static_cast<long long>(changes), static_cast<long long>(c.momentum()[0]),
                static_cast<long long>(c.momentum()[1]), c.omega());
  }
}

namespace {

// Mean U_x over steps 1500..2000 of 8 runs of a disc (M = 40) started at U_x = u0.
double late_velocity(double u0, bool held) {
  double late = 0.0;
  for (int run = 0; run < 8; ++run) {
    auto p = params();
    p.seed = 100 + run;
    FhpLattice l(p, MPI_COMM_SELF);
    l.initialise(0.5, 0.0);
    ColloidParams cp;
    cp.x = 32.0;
    cp.y = 27.0;
    cp.mass = 40.0;
    cp.vx = u0;
    cp.held = held;
    cp.seed_for_rules = p.seed;
    FhpColloid c(cp, l);
    for (int i = 0; i < 2000; ++i) {
      c.apply(l);
      l.step();
      if (i >= 1500)
        late += c.velocity()[0] / (500.0 * 8);
    }
  }
  std::printf("%s disc, M = 40, U0 = %.2f: mean U_x over steps 1500..2000 = %.4f\n",
              held ? "held" : "moving", u0, late);
  return late;
}

// A disc (M = 680) started at U_x = 0.3 on a random gas, 5000 steps of relaxation, then 12 blocks
// of 5000 steps: V_x (checked constant at every block end), the block means of the composite
// velocity U_x and of the centre's displacement per step, with their standard errors.
struct DriftBlocks {
  double v, u, u_error, drift, drift_error;
};

DriftBlocks drift_blocks(bool held) {
  FhpLattice l(params(), MPI_COMM_SELF);
  l.initialise(0.5, 0.0);
  const double lx = l.size_x();
  ColloidParams cp;
  cp.x = 32.0;
  cp.y = 27.0;
  cp.mass = 680.0;
  cp.vx = 0.3;
  cp.held = held;
  cp.seed_for_rules = 21;
  FhpColloid c(cp, l);
  const auto v = c.centre_of_mass_velocity(l);
  EXPECT_GT(v[0], 0.01);
  for (int i = 0; i < 5000; ++i) {
    c.apply(l);
    l.step();
  }
  const int blocks = 12, block = 5000;
  double su = 0.0, su2 = 0.0, sx = 0.0, sx2 = 0.0;
  for (int b = 0; b < blocks; ++b) {
    double m = 0.0, travelled = 0.0, last = c.position()[0];
    for (int i = 0; i < block; ++i) {
      c.apply(l);
      l.step();
      m += c.composite_velocity(l)[0] / block;
      travelled += std::remainder(c.position()[0] - last, lx);
      last = c.position()[0];
    }
    const auto now = c.centre_of_mass_velocity(l);
    EXPECT_EQ(now[0], v[0]);
    EXPECT_EQ(now[1], v[1]);
    su += m;
    su2 += m * m;
    sx += travelled / block;
    sx2 += (travelled / block) * (travelled / block);
  }
  const double mu = su / blocks, mx = sx / blocks;
  const DriftBlocks d{v[0], mu, std::sqrt((su2 / blocks - mu * mu) / (blocks - 1)), mx,
                      std::sqrt((sx2 / blocks - mx * mx) / (blocks - 1))};
  std::printf("%s disc, M = 680, U0 = 0.3: V_x = %.5f, mean composite U_x = %.5f +- %.5f, "
              "centre drift %.5f +- %.5f per step; covered set changed %lld times in %d steps\n",
              held ? "held" : "moving", d.v, d.u, d.u_error, d.drift, d.drift_error,
              static_cast<long long>(c.geometry_rebuilds()), 5000 + blocks * block);
  return d;
}

} // namespace

// A held disc given a velocity loses it to the fluid: with the moving-boundary rule the fluid
// takes up the wall velocity, so the colloid's momentum relaxes towards zero (to thermal
// fluctuations of size sqrt(<v^2>) ~ (kT / M)^(1/2)). Plain bounce-back would leave U without
// any influence on the fluid and U would only random-walk. Averaged over 8 runs the mean U_x
// over steps 1500..2000 must be below half of U_0 (the first run of this test: ~0.1 U_0).
TEST(FhpColloid, HeldDiscHandsItsMomentumToTheFluid) {
  EXPECT_LT(std::abs(late_velocity(0.1, true)), 0.5 * 0.1);
}

// The held colloid fluctuates about the centre-of-mass velocity V = P_total / M_total, not about
// zero: a run's time averages must be taken of U - V (the driver's VACF and D(t) were not, and a
// seed-11 run of the 128 x 128 scene had |V| = 0.26 rms(U): Z bent to a plateau, D(t) to a drift).
// V is conserved exactly at every step; a disc started with U_x = 0.3 (M = 680, so V_x ~ 0.016)
// hands its momentum to the fluid, and the mean composite velocity over steps 5000..65000 equals
// V within 4 standard errors (error from 12 blocks of 5000 steps, >> the relaxation time M/xi).
TEST(FhpColloid, HeldDiscFluctuatesAboutTheCentreOfMassVelocity) {
  const DriftBlocks d = drift_blocks(true);
  EXPECT_NEAR(d.u, d.v, 4.0 * d.u_error);
  EXPECT_GT(std::abs(d.u), 0.5 * d.v); // not about zero
}

// van der Hoef & Frenkel §4.3 scaled down to a test: the held colloid's VACF tail goes as t^-1. A
// light disc (M = 100, R = 2.5; with the gas inside M_c ~ 168) on 128 x 128 sites, 2e6 steps (~20 s
// of CPU): its own velocity relaxation is over by t ~ 300, so the local exponent n of Z(t) over
// lags 300..1000 is near 1. The unsteady-Stokes theory of a disc in a 2D fluid
// (tools/lgca_plot.py held_disc_vacf; nu = 0.092 to 0.097, hydrodynamic radius a = 1.6 to 2.5;
// a = 2.1 fits the M = 680 run of run/lgca_colloid_held.toml within 1-4 % over t = 30..2700)
// gives n = 0.95 to 1.04 there. Z is taken in the P = 0 ensemble plus M_c / (2 M_tot), the box
// correction of colloid_correlations.hpp (0.0017, 6 % of Z(1000)). n from Z averaged over
// +-10 % in t at both ends; its error is the jackknife over 10 blocks of 2e5 steps. Asserted: n
// within 2.5 sigma of the theory's band [0.95, 1.04], with sigma < 0.078 so that the window
// (at most [0.755, 1.235]) excludes t^-0.75 and t^-1.25 tails, the old estimator's ~0.7 and the
// t^-0.5 bug. Measured when written: n = 0.913 +- 0.072. (A 3 sigma window would need sigma <
// 0.065, ~2.5e6 steps; catching the measured tail times t^-0.25 (n ~ 1.16) would need sigma <
// 0.049, ~4.4e6 steps: sigma goes as steps^-1/2.)
// (The drift of U about V that made the old estimator's n ~ 0.5 is caught by the unit test
// ColloidCorrelations.AveragesAreOfTheFluctuationAboutTheReference; here it would give ~0.7.)
TEST(FhpColloid, HeldDiscVacfTailGoesAsInverseTime) {
  FhpParams p = params();
  p.size_x = 128;
  p.size_y = 128;
  p.seed = 11;
  FhpLattice l(p, MPI_COMM_SELF);
  l.initialise(0.5, 0.0);
  ColloidParams cp;
  cp.x = 64.0;
  cp.y = 55.0;
  cp.mass = 100.0;
  cp.seed_for_rules = p.seed;
  FhpColloid c(cp, l);
  for (int i = 0; i < 5000; ++i) {
    c.apply(l);
    l.step();
  }
  const std::int64_t steps = 2000000;
  const int t1 = 300, t2 = 1000;
  ColloidCorrelations stats(1100, 100, 100, steps, c.centre_of_mass_velocity(l));
  for (std::int64_t i = 0; i < steps; ++i) {
    c.apply(l);
    l.step();
    stats.add(c.composite_velocity(l));
  }
  const double m_tot = cp.mass + static_cast<double>(total_mass(l));
  const auto z = stats.vacf(0.5 * c.composite_mass(l) / m_tot);
  const std::size_t n_lags = z.lags.size();
  const auto smooth = [&](const double *curve, int t) {
    double s = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < n_lags; ++k)
      if (z.lags[k] >= t / 1.1 && z.lags[k] <= t * 1.1) {
        s += curve[k];
        ++n;
      }
    return s / n;
  };
  const auto exponent = [&](const double *curve) {
    return -std::log(smooth(curve, t2) / smooth(curve, t1)) / std::log(double(t2) / t1);
  };
  const double n = exponent(z.value.data());
  const int b = stats.blocks();
  std::vector<double> jk(b);
  double mean = 0.0;
  for (int i = 0; i < b; ++i) {
    std::vector<double> rest(n_lags, 0.0);
    for (int j = 0; j < b; ++j)
      if (j != i)
        for (std::size_t k = 0; k < n_lags; ++k)
          rest[k] += z.blocks[j * n_lags + k] / (b - 1);
    jk[i] = exponent(rest.data());
    mean += jk[i] / b;
  }
  double var = 0.0;
  for (double x : jk)
    var += (x - mean) * (x - mean);
  const double sigma = std::sqrt((b - 1.0) / b * var);
  std::printf("held disc M = 100, 128 x 128, %lld steps: Z(%d) = %.4f, Z(%d) = %.4f, local "
              "exponent %d..%d: %.3f +- %.3f (jackknife, %d blocks)\n",
              static_cast<long long>(steps), t1, smooth(z.value.data(), t1), t2,
              smooth(z.value.data(), t2), t1, t2, n, sigma, b);
  // The window: the theory's band widened by 2.5 sigma (a correct code run with another seed
  // falls outside it ~1 % of the time), sigma < 0.078 so that it is at most [0.755, 1.235]: a
  // tail t^-0.75 or t^-1.25 (the exponent off by a quarter) fails, checked below on the same
  // estimator fed the pure power laws on the same lags.
  const auto inside = [&](double e) { return e >= 0.95 - 2.5 * sigma && e <= 1.04 + 2.5 * sigma; };
  EXPECT_LT(sigma, 0.078); // the test must be able to tell t^-1 from t^-0.75 and from t^-1.25
  EXPECT_TRUE(inside(n)) << "n = " << n << " outside [" << 0.95 - 2.5 * sigma << ", "
                         << 1.04 + 2.5 * sigma << "]";
  for (const double q : {0.75, 1.25}) {
    std::vector<double> pure(n_lags);
    for (std::size_t k = 0; k < n_lags; ++k)
      pure[k] = std::pow(static_cast<double>(z.lags[k]), -q);
    const double e = exponent(pure.data());
    EXPECT_NEAR(e, q, 1e-3); // the estimator of a pure power law
    EXPECT_FALSE(inside(e)) << "a t^-" << q << " tail would pass";
  }
}

namespace {

// Brute force over the whole lattice: sites within R of the centre and the links with one end
// inside (what the colloid builds from its bounding box only).
std::array<int, 2> covered_and_links(const FhpLattice &l, std::array<double, 2> c, double r) {
  const int X = l.size_x(), Y = l.size_y();
  const double s = 0.8660254037844386, lx = X, ly = Y * s;
  const auto in = [&](int x, int y) {
    const double dx = std::remainder(x + 0.5 * (y % 2) - c[0], lx);
    const double dy = std::remainder(y * s - c[1], ly);
    return dx * dx + dy * dy <= r * r;
  };
  int sites = 0, links = 0;
  for (int y = 0; y < Y; ++y)
    for (int x = 0; x < X; ++x) {
      const int o = y % 2;
      sites += in(x, y);
      const int nx[3] = {x + 1, x + o, x - 1 + o};
      for (int k = 0; k < 3; ++k)
        links += in(x, y) != in((nx[k] + X) % X, (y + (k > 0)) % Y);
    }
  return {sites, links};
}

} // namespace

// A moving disc (held = false) started at U = (0.3, 0.1) next to the corner of the periodic
// box: it crosses both edges. At every step of 3000: fluid + colloid momentum is conserved
// exactly (covering and uncovering sites moves nothing: the gas fills both sides), the centre
// is the start plus the sum of the velocities after each step (wrapped), and the covered sites
// and boundary links built from the bounding box are those of a brute-force pass over the
// whole lattice.
TEST(FhpColloid, MovingDiscConservesMomentumAcrossThePeriodicEdges) {
  FhpLattice l(params(), MPI_COMM_SELF);
  l.initialise(0.5, 0.0);
  const double lx = l.size_x(), ly = l.size_y() * 0.8660254037844386;
  ColloidParams cp;
  cp.x = 62.7;
  cp.y = ly - 1.3;
  cp.radius = 2.5;
  cp.mass = 200.0;
  cp.vx = 0.3;
  cp.vy = 0.1;
  cp.held = false;
  cp.seed_for_rules = 21;
  FhpColloid c(cp, l);
  const auto f0 = fluid_momentum(l);
  const auto c0 = c.momentum();
  double ux = cp.x, uy = cp.y; // unwrapped: start + sum of velocities
  int wraps_x = 0, wraps_y = 0, geometry_mismatch = 0;
  auto last = c.position();
  for (int i = 0; i < 3000; ++i) {
    c.apply(l);
    const auto v = c.velocity();
    ux += v[0];
    uy += v[1];
    const auto x = c.position();
    wraps_x += std::abs(x[0] - last[0]) > 0.5 * lx;
    wraps_y += std::abs(x[1] - last[1]) > 0.5 * ly;
    last = x;
    ASSERT_NEAR(std::remainder(ux - x[0], lx), 0.0, 1e-9) << "step " << i;
    ASSERT_NEAR(std::remainder(uy - x[1], ly), 0.0, 1e-9) << "step " << i;
    ASSERT_TRUE(x[0] >= 0.0 && x[0] < lx && x[1] >= 0.0 && x[1] < ly) << "step " << i;
    const auto brute = covered_and_links(l, x, cp.radius);
    geometry_mismatch += brute[0] != c.inside_sites() || brute[1] != c.boundary_links();
    l.step();
    const auto f = fluid_momentum(l);
    const auto m = c.momentum();
    ASSERT_EQ(f[0] + m[0], f0[0] + c0[0]) << "step " << i;
    ASSERT_EQ(f[1] + m[1], f0[1] + c0[1]) << "step " << i;
  }
  std::printf("moving disc, M = 200, U0 = (0.3, 0.1): %d + %d crossings of the x and y edges, "
              "travelled (%.2f, %.2f), covered set checked %lld times, changed %lld times in "
              "3000 steps, final U = (%.4f, %.4f)\n",
              wraps_x, wraps_y, ux - cp.x, uy - cp.y, static_cast<long long>(c.geometry_checks()),
              static_cast<long long>(c.geometry_rebuilds()), c.velocity()[0], c.velocity()[1]);
  EXPECT_EQ(geometry_mismatch, 0);
  EXPECT_GE(wraps_x, 1);
  EXPECT_GE(wraps_y, 1);
  EXPECT_GT(c.geometry_rebuilds(), 100); // the disc moved through many site sets
}

// The covered sites and boundary links of a moving disc, built from its bounding box and only
// when the centre has moved farther than the smallest distance of a site from the circle,
// are those of a brute-force pass over the whole lattice at every step, for small to
// box-sized discs (R = 27.5: the box of the disc wraps onto itself) moving steadily (M = 1e6)
// across the periodic edges.
TEST(FhpColloid, MovingDiscGeometryMatchesABruteForcePass) {
  FhpLattice l(params(), MPI_COMM_SELF);
  l.initialise(0.5, 0.0);
  for (const double r : {0.7, 4.2, 12.0, 27.5}) {
    ColloidParams cp;
    cp.x = 60.1;
    cp.y = 3.3;
    cp.radius = r;
    cp.mass = 1e6;
    cp.vx = 0.23;
    cp.vy = -0.17;
    cp.held = false;
    cp.seed_for_rules = 21;
    FhpColloid c(cp, l);
    int mismatch = 0;
    for (int i = 0; i < 200; ++i) {
      c.apply(l);
      const auto brute = covered_and_links(l, c.position(), r);
      mismatch += brute[0] != c.inside_sites() || brute[1] != c.boundary_links();
    }
    std::printf("R = %.1f: %d sites, %d links at the end; covered set checked %lld times, "
                "changed %lld times in 200 steps\n",
                r, c.inside_sites(), c.boundary_links(),
                static_cast<long long>(c.geometry_checks()),
                static_cast<long long>(c.geometry_rebuilds()));
    EXPECT_EQ(mismatch, 0) << "R = " << r;
    EXPECT_GT(c.geometry_rebuilds(), 20) << "R = " << r;
  }
}

// The moving disc's counterpart of HeldDiscHandsItsMomentumToTheFluid: started at U_x = 0.1
// (M = 40) it is slowed by the fluid; averaged over 8 runs the mean U_x over steps 1500..2000
// must be below half of U_0 (V_x = 3e-4 here).
TEST(FhpColloid, MovingDiscHandsItsMomentumToTheFluid) {
  EXPECT_LT(std::abs(late_velocity(0.1, false)), 0.5 * 0.1);
}

// A free disc shares the box's momentum: started at U_x = 0.3 (M = 680, V_x = 0.0157) it
// relaxes to the centre-of-mass velocity V and then drifts with it. Over 12 blocks of 5000
// steps after 5000 steps of relaxation (the relaxation time M / xi is a few hundred steps),
// the mean composite velocity and the centre's displacement per step (the disc's own velocity
// summed: what moves the centre) both equal V_x within 4 standard errors of the block means,
// and are not about zero.
TEST(FhpColloid, MovingDiscDriftsWithTheCentreOfMassVelocity) {
  const DriftBlocks d = drift_blocks(false);
  EXPECT_NEAR(d.u, d.v, 4.0 * d.u_error);
  EXPECT_NEAR(d.drift, d.v, 4.0 * d.drift_error);
  EXPECT_GT(d.u, 0.5 * d.v); // not about zero
  EXPECT_GT(d.drift, 0.5 * d.v);
}

// Refused geometry: a disc as wide as the box, a moving disc with solids, a moving disc that
// can cover no site.
TEST(FhpColloid, RefusesDiscsItCannotRun) {
  FhpLattice l(params(), MPI_COMM_SELF);
  const auto make = [](const ColloidParams &p, const FhpLattice &lattice) {
    const FhpColloid c(p, lattice);
    return c.inside_sites();
  };
  ColloidParams cp;
  cp.x = 32.0;
  cp.y = 27.0;
  cp.radius = 27.8; // 2 R = 55.6 > L_y = 55.4
  EXPECT_THROW(make(cp, l), narrows::Error);
  cp.radius = 27.5;
  EXPECT_NO_THROW(make(cp, l));
  auto p = params();
  p.walls = true;
  FhpLattice walled(p, MPI_COMM_SELF);
  cp.radius = 2.5;
  cp.held = false;
  EXPECT_THROW(make(cp, walled), narrows::Error);
  cp.held = true;
  EXPECT_NO_THROW(make(cp, walled));
  // a moving disc must cover a site wherever it is: radius >= 1/sqrt(3)
  cp.held = false;
  cp.radius = 0.55;
  EXPECT_THROW(make(cp, l), narrows::Error);
  cp.radius = 0.58;
  EXPECT_NO_THROW(make(cp, l));
}
