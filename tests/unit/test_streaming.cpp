// Streaming kernels: free flight and constant force exactly as x + v dt (+ g dt^2/2) with
// periodic wrapping, and the closed-form Kolmogorov kick against a fine RK4 integration.
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace {

using namespace narrows::mpcd;

constexpr double eps = std::numeric_limits<double>::epsilon();

Box make_box(int dim, std::array<int, 3> cells) { return make_periodic_box(dim, cells); }

// Correctly rounded periodic image in [0, L) of y (fmod is exact; only the final + L of a
// negative remainder rounds). Independent of the library's subtract-first strategy.
double ref_wrap(double y, double L) {
  double r = std::fmod(y, L); // exact, sign of y
  if (r < 0.0)
    r += L;
  if (r >= L)
    r = 0.0;
  return r;
}

Fluid fluid_from(int dim, const std::vector<std::array<double, 6>> &rows) {
  Fluid f;
  f.dim = dim;
  f.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    f.id[i] = i;
    for (int k = 0; k < dim; ++k) {
      f.x[k][i] = rows[i][k];
      f.v[k][i] = rows[i][3 + k];
    }
  }
  return f;
}

TEST(StreamFree, ExactDyadicDisplacementAndWrap) {
  const Box box = make_box(3, {8, 6, 5});
  const double dt = 0.25;
  // x, y, z, vx, vy, vz: inside, crossing once each way, more than one box length (both
  // directions), landing exactly on L, landing exactly on 0, landing exactly on -L and 2L.
  // Dyadic values: every sum and product is exact in double, so "exactly x + v dt" does not
  // depend on the evaluation order.
  const std::vector<std::array<double, 6>> rows = {
      {1.5, 2.25, 0.125, 0.5, -0.25, 1.0},
      {7.875, 0.125, 4.5, 1.0, -1.0, 4.0},
      {0.0, 5.9375, 0.0, 100.0, -100.0, 33.0},
      {4.0, 3.0, 2.5, 16.0, 12.0, 10.0},
      {2.0, 1.5, 1.25, -8.0, -6.0, -5.0},
      {4.0, 3.0, 2.5, -48.0, -36.0, -30.0},
      {6.0, 1.0, 4.0, 8.0, 20.0, 4.0},
      {0.5, 0.5, 0.5, -2.0, -2.0, -2.0},
      {7.9990234375, 0.0, 0.0, 0.00390625, 0.0, -0.0078125},
      {3.0, 3.0, 3.0, 1000.5, -1000.25, 999.75},
      {0.0, 0.0, 0.0, -64.0, -48.0, -40.0}};
  Fluid f = fluid_from(3, rows);
  stream_free(f, box, dt);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double L = box.length[k];
      const double y = rows[i][k] + rows[i][3 + k] * dt; // exact for these dyadic values
      const double want = ref_wrap(y, L);
      EXPECT_EQ(f.x[k][i], want) << "particle " << i << " axis " << k << " unwrapped " << y;
      EXPECT_GE(f.x[k][i], 0.0);
      EXPECT_LT(f.x[k][i], L);
      EXPECT_EQ(f.v[k][i], rows[i][3 + k]) << "free flight must not change v";
    }
  // Spot checks of the periodic images, written out by hand.
  EXPECT_EQ(f.x[0][1], 0.125);  // 7.875 + 0.25 = 8.125 -> 0.125
  EXPECT_EQ(f.x[1][1], 5.875);  // 0.125 - 0.25 -> 5.875
  EXPECT_EQ(f.x[0][3], 0.0);    // 4 + 4 = 8 = L -> 0
  EXPECT_EQ(f.x[1][3], 0.0);    // 3 + 3 = 6 = L -> 0
  EXPECT_EQ(f.x[2][4], 0.0);    // 1.25 - 1.25 = 0
  EXPECT_EQ(f.x[0][5], 0.0);    // 4 - 12 = -8 = -L -> 0
  EXPECT_EQ(f.x[1][6], 0.0);    // 1 + 5 = 6 = L -> 0
  EXPECT_EQ(f.x[0][2], 1.0);    // 0 + 25 = 25 -> 1
  EXPECT_EQ(f.x[1][2], 4.9375); // 5.9375 - 25 = -19.0625 -> -19.0625 + 24
  EXPECT_EQ(f.x[2][2], 3.25);   // 0 + 8.25 -> 3.25
  EXPECT_EQ(f.x[0][8], 0.0);    // 7.9990234375 + 2^-10 = 8 = L exactly -> 0
  EXPECT_EQ(f.x[2][8], 5.0 - 0.001953125);
  EXPECT_EQ(f.x[0][9], 5.125);  // 253.125 - 31 * 8
  EXPECT_EQ(f.x[1][9], 4.9375); // -247.0625 + 42 * 6
  EXPECT_EQ(f.x[0][10], 0.0);   // -16 = -2L
  EXPECT_EQ(f.x[1][10], 0.0);   // -12 = -2L
  EXPECT_EQ(f.x[2][10], 0.0);   // -10 = -2L
}

TEST(StreamFree, Random2DWithinRoundingAndWrapped) {
  const Box box = make_box(2, {17, 9, 1});
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> ux(0.0, 1.0), uv(-60.0, 60.0);
  const std::size_t n = 20000;
  Fluid f;
  f.dim = 2;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = i;
    for (int k = 0; k < 2; ++k) {
      f.x[k][i] = ux(gen) * box.length[k];
      f.v[k][i] = (i % 3 == 0) ? uv(gen) : uv(gen) * 0.01;
    }
  }
  const Fluid before = f;
  const double dt = 0.1;
  stream_free(f, box, dt);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k) {
      const double L = box.length[k];
      const double y = before.x[k][i] + before.v[k][i] * dt;
      const double want = ref_wrap(y, L);
      // No tolerance: with integer L, y - n L is exact for |y| < 2^52, so the correctly
      // rounded image is unique and any correct wrap returns exactly ref_wrap(y).
      ASSERT_EQ(f.x[k][i], want) << "particle " << i << " axis " << k << " unwrapped " << y;
      ASSERT_GE(f.x[k][i], 0.0);
      ASSERT_LT(f.x[k][i], L);
      ASSERT_EQ(f.v[k][i], before.v[k][i]);
    }
}

TEST(StreamFree, TinyNegativeDisplacementFromZeroWrapsBelowL) {
  // -1e-300 + L rounds to L, which must come back as 0, never as L.
  const Box box = make_box(2, {4, 4, 1});
  Fluid f = fluid_from(2, {{0.0, 0.0, 0, -1e-300, -1e-17, 0}, {1e-18, 0.0, 0, -1.0, 0.0, 0}});
  stream_free(f, box, 1.0);
  for (std::size_t i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(f.x[k][i], 0.0);
      EXPECT_LT(f.x[k][i], box.length[k]) << "particle " << i << " axis " << k;
    }
  EXPECT_EQ(f.x[0][1], 3.0); // 1e-18 - 1 -> -1 (rounded) -> 3
}

TEST(StreamConstantForce, ExactDyadic3D) {
  const Box box = make_box(3, {8, 6, 5});
  const double dt = 0.5;
  const std::array<double, 3> g = {0.25, -3.0, 40.0};
  const std::vector<std::array<double, 6>> rows = {
      {1.5, 2.25, 0.125, 0.5, -0.25, 1.0},     {7.875, 0.125, 4.5, 1.0, -1.0, 4.0},
      {0.0, 5.9375, 0.0, 100.0, -100.0, 33.0}, {4.0, 3.0, 2.5, 7.875, 6.375, -15.0},
      {2.0, 1.5, 1.25, -8.0, -6.0, -5.0},      {3.0, 3.0, 3.0, 1000.5, -1000.25, 999.75}};
  Fluid f = fluid_from(3, rows);
  stream_constant_force(f, box, dt, g);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double L = box.length[k];
      const double y = rows[i][k] + rows[i][3 + k] * dt + 0.5 * g[k] * dt * dt; // exact
      EXPECT_EQ(f.x[k][i], ref_wrap(y, L)) << "particle " << i << " axis " << k;
      EXPECT_GE(f.x[k][i], 0.0);
      EXPECT_LT(f.x[k][i], L);
      EXPECT_EQ(f.v[k][i], rows[i][3 + k] + g[k] * dt) << "particle " << i << " axis " << k;
    }
  // Hand-checked: 4 + 7.875*0.5 + 0.25*0.125 = 7.96875 ; vx = 7.875 + 0.125 = 8.
  EXPECT_EQ(f.x[0][3], 7.96875);
  EXPECT_EQ(f.v[0][3], 8.0);
  // z: 2.5 - 7.5 + 5 = 0 exactly.
  EXPECT_EQ(f.x[2][3], 0.0);
  // y: 3 + 3.1875 - 0.375 = 5.8125.
  EXPECT_EQ(f.x[1][3], 5.8125);
}

TEST(StreamConstantForce, Random2DWithinRounding) {
  const Box box = make_box(2, {12, 7, 1});
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> ux(0.0, 1.0), uv(-30.0, 30.0);
  const std::size_t n = 20000;
  Fluid f;
  f.dim = 2;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = i;
    for (int k = 0; k < 2; ++k) {
      f.x[k][i] = ux(gen) * box.length[k];
      f.v[k][i] = uv(gen);
    }
  }
  const Fluid before = f;
  const double dt = 0.37;
  const std::array<double, 3> g = {0.013, -2.5, 0.0};
  stream_constant_force(f, box, dt, g);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k) {
      const double L = box.length[k];
      const long double y = static_cast<long double>(before.x[k][i]) +
                            static_cast<long double>(before.v[k][i]) * dt +
                            0.5L * g[k] * static_cast<long double>(dt) * dt;
      const double want = ref_wrap(static_cast<double>(y), L);
      // Three double roundings of terms up to |x| + |v dt| + |g| dt^2 (< 24), then the wrap
      // rounding: 8 ulp of that magnitude bounds them.
      const double mag = std::abs(before.x[k][i]) + std::abs(before.v[k][i] * dt) + L;
      double d = std::abs(f.x[k][i] - want);
      d = std::min(d, L - d);
      ASSERT_LE(d, 8 * eps * mag) << "particle " << i << " axis " << k;
      ASSERT_GE(f.x[k][i], 0.0);
      ASSERT_LT(f.x[k][i], L);
      // v + g dt: one product and one sum, 2 ulp of |v| + |g dt|.
      ASSERT_LE(std::abs(f.v[k][i] - (before.v[k][i] + g[k] * dt)),
                2 * eps * (std::abs(before.v[k][i]) + std::abs(g[k] * dt)));
    }
}

// Fine RK4 of X' = V, V' = A sin(theta0 + phi t/dt) from X = V = 0 over [0, dt], in long
// double: V(dt) is the kick dv, X(dt) the displacement beyond v_x dt.
SineKick rk4_kick(double theta0, double phi, double A, double dt) {
  // h w <= 5e-4: Simpson/RK4 error (h w)^4 / 180 ~ 4e-16 relative to |A| dt.
  const int steps = 2000 + static_cast<int>(2000 * std::abs(phi));
  const long double h = static_cast<long double>(dt) / steps;
  const long double w = static_cast<long double>(phi) / dt;
  auto acc = [&](long double t) {
    return static_cast<long double>(A) * std::sin(static_cast<long double>(theta0) + w * t);
  };
  long double X = 0, V = 0, a0 = acc(0);
  for (int s = 0; s < steps; ++s) {
    const long double t = s * h;
    const long double k1x = V, k1v = a0;
    const long double k2x = V + 0.5L * h * k1v, k2v = acc(t + 0.5L * h);
    const long double k3x = V + 0.5L * h * k2v, k3v = k2v;
    const long double k4x = V + h * k3v, k4v = acc((s + 1) * h);
    a0 = k4v;
    X += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    V += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {static_cast<double>(X), static_cast<double>(V)};
}

TEST(StreamSine, KickMatchesRK4) {
  const double phis[] = {0.0, 1e-9, -1e-9, 1e-4, 0.05, 0.0999, 0.1001, 1.0, 30.0, -2.0, -0.07};
  const double thetas[] = {0.0, 0.3, 1.5707963267948966, 2.5, -1.1, 4.0};
  const double As[] = {1.0, -0.37, 2.5e-3};
  const double dts[] = {0.1, 1.0};
  for (double dt : dts)
    for (double A : As)
      for (double th : thetas)
        for (double phi : phis) {
          const SineKick got = sine_kick(th, phi, A, dt);
          const SineKick ref = rk4_kick(th, phi, A, dt);
          // Relative 1e-10 (RK4 with h w <= 5e-4 is good to ~4e-16 relative; the closed form
          // loses at most ~6 eps/phi^2 ~ 1e-13 to cancellation just above the switch), plus an
          // absolute floor of 1e-14 of the kick scale (|A| dt, |A| dt^2) for results near zero.
          const double tol_v = 1e-10 * std::abs(ref.dv) + 1e-14 * std::abs(A) * dt;
          const double tol_x = 1e-10 * std::abs(ref.dx) + 1e-14 * std::abs(A) * dt * dt;
          EXPECT_NEAR(got.dv, ref.dv, tol_v)
              << "dv: theta0 " << th << " phi " << phi << " A " << A << " dt " << dt;
          EXPECT_NEAR(got.dx, ref.dx, tol_x)
              << "dx: theta0 " << th << " phi " << phi << " A " << A << " dt " << dt;
        }
}

TEST(StreamSine, KickZeroPhiIsConstantForce) {
  // phi = 0: constant acceleration A sin(theta0): dv = A S dt, dx = A S dt^2 / 2.
  for (double th : {0.0, 0.7, -2.0, 3.0}) {
    const double A = 0.8, dt = 0.3;
    const SineKick k = sine_kick(th, 0.0, A, dt);
    // Two or three products: 4 ulp.
    EXPECT_NEAR(k.dv, A * std::sin(th) * dt, 4 * eps * A * dt);
    EXPECT_NEAR(k.dx, 0.5 * A * std::sin(th) * dt * dt, 4 * eps * A * dt * dt);
  }
}

// The kick's sines and cosines are polynomials after an exact reduction by pi/2 (fdlibm's
// kernels, vectorised), not libm's calls: against the closed form with libm's std::sin and
// std::cos they agree to round-off wherever the closed form holds (|phi| >= 0.1), up to the
// reduction's limit 2^19 and beyond it, where libm's are used: there bitwise.
TEST(StreamSine, KickAgreesWithLibmClosedForm) {
  const auto closed = [](double th, double phi, double A, double dt) {
    const double S = std::sin(th), C = std::cos(th), s = std::sin(phi), c = std::cos(phi);
    const double sinc = s / phi, c1 = (1.0 - c) / phi, c2 = c1 / phi, c3 = (phi - s) / (phi * phi);
    return SineKick{A * dt * dt * std::fma(S, c2, C * c3), A * dt * std::fma(S, sinc, C * c1)};
  };
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> theta(0.0, 2.0 * std::numbers::pi), log_phi(-1.0, 5.7);
  const double A = 0.3, dt = 0.5;
  for (int t = 0; t < 20000; ++t) {
    const double th = theta(gen), phi = (t % 2 ? -1.0 : 1.0) * std::pow(10.0, log_phi(gen));
    const SineKick got = sine_kick(th, phi, A, dt), want = closed(th, phi, A, dt);
    // The closed form's own cancellation near |phi| = 0.1 (~6 eps / phi^2 relative), a few ulp
    // of the sines, and the reduction's error n 2^-53 pi/2 for n ~ 2 |phi| / pi: 1e-12 of the
    // kick scale plus 2e-16 |phi| of it.
    const double tol = (1e-12 + 2e-16 * std::abs(phi)) * std::abs(A) * dt;
    ASSERT_NEAR(got.dv, want.dv, tol) << "theta0 " << th << " phi " << phi;
    ASSERT_NEAR(got.dx, want.dx, tol * dt) << "theta0 " << th << " phi " << phi;
  }
  for (double phi : {0x1p19 * 1.0000001, 1e7, -3e9}) { // beyond the reduction: libm's
    const SineKick got = sine_kick(1.2, phi, A, dt), want = closed(1.2, phi, A, dt);
    EXPECT_EQ(got.dv, want.dv) << "phi " << phi;
    EXPECT_EQ(got.dx, want.dx) << "phi " << phi;
  }
}

TEST(StreamSine, ContinuousAcrossSeriesSwitch) {
  // The series (|phi| < 0.1) and the closed form meet at |phi| = 0.1. Across one ulp of phi
  // the true functions change by ~1e-17 relative; the closed form is accurate to ~6 eps/phi^2
  // = 1.3e-13 relative at phi = 0.1 and the series truncation to ~1.5e-15, so 1e-12 of the
  // kick scale bounds any jump.
  for (double sign : {1.0, -1.0})
    for (double th : {0.0, 0.4, 1.3, 2.9, -0.8}) {
      const double A = 1.3, dt = 0.7;
      const double at = sign * 0.1;
      const double below = std::nextafter(at, 0.0);
      const double above = std::nextafter(at, sign * 1.0);
      const SineKick a = sine_kick(th, below, A, dt);
      const SineKick b = sine_kick(th, at, A, dt);
      const SineKick c = sine_kick(th, above, A, dt);
      EXPECT_NEAR(a.dv, b.dv, 1e-12 * A * dt) << "theta0 " << th << " sign " << sign;
      EXPECT_NEAR(b.dv, c.dv, 1e-12 * A * dt) << "theta0 " << th << " sign " << sign;
      EXPECT_NEAR(a.dx, b.dx, 1e-12 * A * dt * dt) << "theta0 " << th << " sign " << sign;
      EXPECT_NEAR(b.dx, c.dx, 1e-12 * A * dt * dt) << "theta0 " << th << " sign " << sign;
    }
}

// Checks stream_sine_force against sine_kick particle by particle.
void check_sine_stream(int dim) {
  const Box box = dim == 3 ? make_box(3, {10, 16, 6}) : make_box(2, {10, 16, 1});
  std::mt19937_64 gen(dim);
  std::uniform_real_distribution<double> ux(0.0, 1.0), uv(-3.0, 3.0);
  const std::size_t n = 5000;
  Fluid f;
  f.dim = dim;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = i;
    for (int k = 0; k < dim; ++k) {
      f.x[k][i] = ux(gen) * box.length[k];
      f.v[k][i] = uv(gen);
    }
    if (i % 50 == 0)
      f.v[1][i] = 0.0; // phi = 0
    if (i % 50 == 1)
      f.v[1][i] = 1e-12; // deep in the series branch
    if (i % 50 == 2)
      f.v[0][i] = 40.0; // crosses the box in x
  }
  const Fluid before = f;
  const double dt = 0.5, A = 0.2;
  stream_sine_force(f, box, dt, A);
  const double kw = 2.0 * std::numbers::pi / box.length[1];
  for (std::size_t i = 0; i < n; ++i) {
    const SineKick kick =
        sine_kick(kw * before.x[1][i], kw * before.v[1][i] * dt, A, dt); // same arguments
    const double want_x = ref_wrap(before.x[0][i] + before.v[0][i] * dt + kick.dx, box.length[0]);
    const double want_vx = before.v[0][i] + kick.dv;
    const double want_y = ref_wrap(before.x[1][i] + before.v[1][i] * dt, box.length[1]);
    // y, z and v_x are computed by the same expressions and wrapped exactly (see
    // StreamFree.Random2D...), so they must agree bitwise; x sums its terms in another order.
    // Sums of up to three terms of magnitude <= |x| + |v dt| + |dx| + L (< 60): 4 ulp of that.
    auto close = [](double got, double want, double L, double mag) {
      double d = std::abs(got - want);
      d = std::min(d, L - d);
      return d <= 4 * eps * mag;
    };
    const double magx = box.length[0] + std::abs(before.v[0][i] * dt) + std::abs(kick.dx);
    ASSERT_TRUE(close(f.x[0][i], want_x, box.length[0], magx))
        << "x of particle " << i << ": " << f.x[0][i] << " vs " << want_x;
    ASSERT_EQ(f.v[0][i], want_vx) << "vx of particle " << i;
    ASSERT_EQ(f.x[1][i], want_y) << "y of particle " << i;
    ASSERT_EQ(f.v[1][i], before.v[1][i]) << "vy must not change";
    if (dim == 3) {
      const double want_z = ref_wrap(before.x[2][i] + before.v[2][i] * dt, box.length[2]);
      ASSERT_EQ(f.x[2][i], want_z) << "z of particle " << i;
      ASSERT_EQ(f.v[2][i], before.v[2][i]) << "vz must not change";
    }
    for (int k = 0; k < dim; ++k) {
      ASSERT_GE(f.x[k][i], 0.0) << "particle " << i << " axis " << k;
      ASSERT_LT(f.x[k][i], box.length[k]) << "particle " << i << " axis " << k;
    }
  }
}

TEST(StreamSine, Force2DConsistentWithKick) { check_sine_stream(2); }
TEST(StreamSine, Force3DConsistentWithKick) { check_sine_stream(3); }

TEST(StreamSine, ForceUsesSineOfYAgainstRK4) {
  // End to end: one particle, exact trajectory from RK4 with theta0 = 2 pi y/L_y.
  const Box box = make_box(2, {20, 8, 1});
  Fluid f = fluid_from(2, {{3.0, 1.7, 0, 0.4, 0.9, 0}});
  const double dt = 0.3, A = 0.05;
  stream_sine_force(f, box, dt, A);
  const double kw = 2.0 * std::numbers::pi / 8.0;
  const SineKick ref = rk4_kick(kw * 1.7, kw * 0.9 * dt, A, dt);
  // Relative 1e-10 as in KickMatchesRK4 (+ rounding of x ~ 1 ulp of 4).
  EXPECT_NEAR(f.v[0][0], 0.4 + ref.dv, 1e-10 * std::abs(ref.dv) + 4 * eps);
  EXPECT_NEAR(f.x[0][0], 3.0 + 0.4 * dt + ref.dx, 1e-10 * std::abs(ref.dx) + 8 * eps * 4);
  EXPECT_NEAR(f.x[1][0], 1.7 + 0.9 * dt, 8 * eps * 2);
}

} // namespace
