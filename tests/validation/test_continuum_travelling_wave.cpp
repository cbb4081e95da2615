// Travelling waves of the jamming model (Kanehl (thesis) §6.3.3-6.3.5; issue 22, acceptance 3) with
// the fit of Table 6.2 for mu = 1 and sigma = D = 1 (the thesis' normalisation):
// - the fixed points of the co-moving ODEs (eq 6.13-6.14) at the parameters of fig 6.18 b)
//   (c = -2.8, q = 2.228) are those the thesis describes: three, a saddle on the free-flow branch,
//   a focus at phi_c between them and a saddle on the jammed branch; Eigen's eigenvalues agree
//   with the closed form eq 6.20;
// - on the Hopf line (eq 6.21) the focus has purely imaginary eigenvalues and changes from sink
//   to source as |c| grows across it, and the line is the neutral curve of eq 6.11;
// - the limit cycle around the focus (the thesis' periodic pulse train of fig 6.18 b) exists, and
//   the PDE started from it travels at c and keeps its shape;
// - a pulse grown in the PDE from a small perturbation is a travelling wave of eq 6.13-6.14 at
//   its measured (c, q), next to the homoclinic loop of the jammed saddle.
#include "narrows/engines/continuum/jamming_model.hpp"
#include "narrows/engines/continuum/jamming_solver.hpp"
#include "narrows/engines/continuum/jamming_stability.hpp"
#include "narrows/engines/continuum/travelling_wave.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace narrows;
using namespace narrows::continuum;

namespace {

JammingModel mu1() { return JammingModel(table_6_2(scene::JammingFit::mu_1), 1.0, 1.0); }

void print(double c, double q, const std::vector<FixedPoint> &fps) {
  std::printf("  c = %g, q = %g: %zu fixed points\n", c, q, fps.size());
  for (const auto &f : fps)
    std::printf("    phi0 = %.6f v0 = %.6f  lambda = %+.4f%+.4fi, %+.4f%+.4fi  %s\n", f.phi, f.v,
                f.lambda[0].real(), f.lambda[0].imag(), f.lambda[1].real(), f.lambda[1].imag(),
                to_string(f.type));
}

// Eq 6.20 as printed (sigma = D = 1).
std::array<std::complex<double>, 2> eq_6_20(const JammingModel &m, double c, double phi0) {
  const double v0 = m.vss(phi0), xi = m.xi(phi0), dxi = m.dxi(phi0);
  const double half_trace = 0.5 * (v0 - c - xi / (v0 - c));
  const std::complex<double> root = std::sqrt(
      std::complex<double>(half_trace * half_trace + xi - v0 * phi0 / (v0 - c) * dxi, 0.0));
  return {half_trace + root, half_trace - root};
}

TEST(JammingWave, FixedPointsOfFig6_18b) {
  const JammingModel m = mu1();
  const double c = -2.8, q = 2.228;
  const auto fps = fixed_points(m, c, q);
  print(c, q, fps);
  ASSERT_EQ(fps.size(), 3u);
  const double phi_c = m.fit().phi_c;
  EXPECT_LT(fps[0].phi, phi_c - 0.02); // free-flow branch
  EXPECT_EQ(fps[0].type, FixedPointType::saddle);
  EXPECT_NEAR(fps[1].phi, phi_c, 2.0 * m.fit().dphi); // in the jump of v_ss
  EXPECT_TRUE(fps[1].type == FixedPointType::focus_sink ||
              fps[1].type == FixedPointType::focus_source);
  EXPECT_GT(fps[2].phi, phi_c + 0.01); // jammed branch
  EXPECT_EQ(fps[2].type, FixedPointType::saddle);
  for (const auto &f : fps) {
    EXPECT_NEAR(q, f.phi * (f.v - c), 1e-12); // eq 6.18
    const auto l = eq_6_20(m, c, f.phi);
    // The two eigenvalues in either order.
    const double d0 = std::abs(l[0] - f.lambda[0]) + std::abs(l[1] - f.lambda[1]);
    const double d1 = std::abs(l[0] - f.lambda[1]) + std::abs(l[1] - f.lambda[0]);
    EXPECT_LT(std::min(d0, d1), 1e-9 * (1.0 + std::abs(l[0]) + std::abs(l[1])));
  }
}

// The thesis' statements on the phase portraits (§6.3.4, fig 6.15 a and 6.12), over a grid of
// (c, q) with c from -4 to -1.2 and q from 1 to 3.5 whose fixed points all lie below
// phi_q - 0.005 (at phi_q = 0.845 the fit's v_ss touches 0 and rises again beyond, where a lone
// fixed point can be a node source: outside the physical range, left out): with one fixed point it
// is a saddle; with three, the outer two are saddles (free-flow and jammed branch, either side of
// phi_c) and the middle one a node or a focus; two occur only at tangencies (none on the grid).
TEST(JammingWave, FixedPointTypesOverTheCQPlane) {
  const JammingModel m = mu1();
  int one = 0, three = 0;
  for (int i = 0; i <= 56; ++i)
    for (int j = 0; j <= 250; ++j) {
      const double c = -4.0 + 0.05 * i, q = 1.0 + 0.01 * j;
      const auto fps = fixed_points(m, c, q, 1e-3, 0.999, 4000);
      if (fps.empty() || fps.back().phi >= m.fit().phi_q - 0.005)
        continue; // a root at phi >= phi_q
      ASSERT_TRUE(fps.size() == 1 || fps.size() == 3) << c << " " << q << ": " << fps.size();
      if (fps.size() == 1) {
        ++one;
        EXPECT_EQ(fps[0].type, FixedPointType::saddle) << c << " " << q;
      } else {
        ++three;
        EXPECT_EQ(fps[0].type, FixedPointType::saddle) << c << " " << q;
        EXPECT_EQ(fps[2].type, FixedPointType::saddle) << c << " " << q;
        EXPECT_NE(fps[1].type, FixedPointType::saddle) << c << " " << q;
        EXPECT_LT(fps[0].phi, m.fit().phi_c);
        EXPECT_GT(fps[2].phi, m.fit().phi_c);
      }
    }
  std::printf("  %d (c, q) with one fixed point (saddle), %d with three\n", one, three);
  EXPECT_GT(three, 100);
}

TEST(JammingWave, HopfLineOfEq6_21) {
  const JammingModel m = mu1();
  for (double phi0 : {0.758, 0.76, 0.762, 0.764}) {
    bool valid = false;
    const double c = hopf_speed(m, phi0, &valid);
    ASSERT_TRUE(valid) << phi0;
    const FixedPoint at = classify(m, c, phi0);
    std::printf("  phi0 = %g: Hopf at c = %.6f, lambda = %+.2e%+.4fi\n", phi0, c,
                at.lambda[0].real(), at.lambda[0].imag());
    EXPECT_LT(std::abs(at.lambda[0].real()), 1e-9 * std::abs(at.lambda[0].imag()));
    EXPECT_EQ(classify(m, c + 0.01, phi0).type, FixedPointType::focus_sink);
    EXPECT_EQ(classify(m, c - 0.01, phi0).type, FixedPointType::focus_source);
  }
}

// The Hopf line of the travelling-wave ODEs (eq 6.21) is the neutral curve of the PDE's linear
// stability (eq 6.11): a neutral mode exp(i k (x - c t)) of the PDE is a solution exp(i k z) of
// the linearised eq 6.13-6.14, so at each phi0 the edge k_c of the unstable band of eq 6.11
// equals the Hopf frequency omega_H, and its phase velocity -Im lambda(k_c) / k_c equals c_H.
// Both sides come from different code (the band edge by bisection of eq 6.11, the Hopf point
// in closed form with Eigen's eigenvalues); agreement to 1e-8 (the bisection stops at 1e-14).
TEST(JammingWave, HopfLineIsTheNeutralCurveOfEq6_11) {
  const JammingModel m = mu1();
  for (double phi0 : {0.6, 0.7, 0.75, 0.755, 0.76}) {
    const double kc = unstable_band_edge(m, phi0, 10.0, 20000);
    ASSERT_GT(kc, 0.0) << phi0;
    const double c_phase = -growth_rate(m, phi0, kc).imag() / kc;
    bool valid = false;
    const double c_hopf = hopf_speed(m, phi0, &valid);
    ASSERT_TRUE(valid);
    const double omega = std::abs(classify(m, c_hopf, phi0).lambda[0].imag());
    std::printf("  phi0 = %g: k_c = %.9f, omega_H = %.9f; phase velocity %.9f, c_H = %.9f\n", phi0,
                kc, omega, c_phase, c_hopf);
    EXPECT_NEAR(omega, kc, 1e-8 * kc);
    EXPECT_NEAR(c_phase, c_hopf, 1e-8 * std::abs(c_hopf));
  }
}

// The periodic profile (values at z_j = j P / n) at x, linearly interpolated.
double periodic_at(const std::vector<double> &y, double period, double x) {
  const double n = static_cast<double>(y.size());
  double s = std::fmod(x / period * n, n);
  if (s < 0.0)
    s += n;
  const std::size_t j = static_cast<std::size_t>(s);
  const double w = s - static_cast<double>(j);
  return (1.0 - w) * y[j % y.size()] + w * y[(j + 1) % y.size()];
}

// The speed of the PDE started from the limit cycle: the phase of the Fourier mode of the
// pulse train, sampled often enough that the train moves less than half a wavelength between
// samples. The cycle is tabulated at dz = 1e-3 (interpolation error ~1e-7 in phi), the PDE runs
// at cfl 0.1 (splitting error ~1e-4 in the linear test): 0.5 % is a generous bound on the
// speed; the shape (min and max of phi) must persist to 1 % of its amplitude over t = 20
// (the pulse train is stable in the PDE, as the thesis' simulations show pulse trains).
TEST(JammingWave, LimitCycleOfFig6_18bIsAPulseTrainOfThePDE) {
  const JammingModel m = mu1();
  const double c = -2.8, q = 2.228;
  const auto fps = fixed_points(m, c, q);
  ASSERT_EQ(fps.size(), 3u);
  const LimitCycle lc = limit_cycle(m, c, q, fps[1], 1e-3);
  ASSERT_TRUE(lc.found);
  std::printf("  limit cycle: period %.6f in z, phi from %.6f to %.6f (mean %.6f)\n", lc.period,
              lc.phi_min, lc.phi_max, lc.phi_mean);
  EXPECT_LT(lc.phi_min, fps[1].phi);
  EXPECT_GT(lc.phi_max, fps[1].phi);
  EXPECT_GT(lc.phi_min, fps[0].phi); // inside the saddles: not yet homoclinic
  EXPECT_LT(lc.phi_max, fps[2].phi);

  const int periods = 4, cells = 256;
  const double L = periods * lc.period, dx = L / cells;
  std::vector<double> phi(cells), v(cells);
  for (int i = 0; i < cells; ++i) {
    phi[i] = periodic_at(lc.phi, lc.period, i * dx);
    v[i] = periodic_at(lc.v, lc.period, i * dx);
  }
  JammingSolver solver(m, cells, L);
  const double k = 2.0 * std::numbers::pi * periods / L;
  const double dt = 0.1 * dx / 2.64; // cfl 0.1 at the speed bound of the scenes
  const auto phase = [&] {
    std::complex<double> s = 0.0;
    for (int i = 0; i < cells; ++i)
      s += phi[i] * std::polar(1.0, -k * i * dx);
    return std::arg(s);
  };
  const int per_sample = 100; // the train moves 0.38 < half a wavelength (1.17) per sample
  double t = 0.0, last = phase(), travelled = 0.0;
  while (t < 20.0) {
    for (int j = 0; j < per_sample; ++j)
      solver.step(phi, v, dt);
    t += per_sample * dt;
    double d = phase() - last;
    d -= 2.0 * std::numbers::pi * std::round(d / (2.0 * std::numbers::pi));
    travelled += d;
    last += d;
  }
  const double speed = -travelled / (k * t);
  const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
  std::printf("  PDE from the cycle: speed %.6f (c = %g, rel. error %.2e) over t = %.3f; phi "
              "from %.6f to %.6f\n",
              speed, c, (speed - c) / std::abs(c), t, *lo, *hi);
  EXPECT_LT(std::abs(speed - c), 0.005 * std::abs(c));
  const double amplitude = lc.phi_max - lc.phi_min;
  EXPECT_LT(std::abs(*lo - lc.phi_min), 0.01 * amplitude);
  EXPECT_LT(std::abs(*hi - lc.phi_max), 0.01 * amplitude);
}

} // namespace

namespace {

// Spectral derivative of a periodic array on [0, L).
std::vector<double> derivative(const std::vector<double> &y, double L) {
  const std::size_t n = y.size();
  std::vector<double> out(n, 0.0);
  for (std::size_t m = 1; m < n / 2; ++m) {
    std::complex<double> a = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      a += y[i] * std::polar(1.0, -2.0 * std::numbers::pi * double(m * i) / double(n));
    a *= 2.0 / double(n);
    const double k = 2.0 * std::numbers::pi * double(m) / L;
    for (std::size_t i = 0; i < n; ++i)
      out[i] += (std::complex<double>(0.0, k) * a *
                 std::polar(1.0, 2.0 * std::numbers::pi * double(m * i) / double(n)))
                    .real();
  }
  return out;
}

// A pulse grown in the PDE from a small perturbation of unstable flow (phi = 0.75, one pulse in
// L = 20) is a travelling wave of eq 6.13-6.14: after it settles (t = 250), its speed c (the
// phase of its Fourier mode over t = 250..300) and the co-moving flux q = (v - c) phi - phi'
// (spectral derivatives) make q constant along the profile, and v' = (1 - xi v)/(v - c) (eq
// 6.14) holds along it up to a discretisation residual that shrinks with the grid (rms 21-22 %,
// 5-8 %, 2.3 % of rms |v'| on 128, 256, 512 points, varying with where the fronts fall on the
// grid: they cross phi_c, where xi changes by a factor 2 within dphi = 0.0025); the speed is
// eq 6.15, c = (phi_j v_j - phi v) / (phi_j - phi) between the extremes of the profile; the ODE at
// (c, q) has the three fixed points of fig 6.18 a), and the jam of the pulse sits at the jammed
// saddle (max phi within 1e-3 of its phi0): the PDE pulse train is the orbit near the homoclinic
// loop of that saddle, the thesis' solitary rarefaction pulse (§6.3.5). About 5 s (two grids).
struct Pulse {
  double c = 0.0, q = 0.0, q_spread = 0.0, residual = 0.0, phi_min = 0.0, phi_max = 0.0;
  double c_6_15 = 0.0; // eq 6.15 from the profile's extremes
};

Pulse grow_pulse(const JammingModel &m, int cells) {
  const double L = 20.0, dx = L / cells, dt = 0.1 * dx / 2.64;
  std::vector<double> phi(cells), v(cells);
  for (int i = 0; i < cells; ++i) {
    phi[i] = 0.75 + 1e-3 * std::sin(2.0 * std::numbers::pi * i * dx / L);
    v[i] = m.vss(phi[i]);
  }
  JammingSolver solver(m, cells, L);
  const auto phase = [&] {
    std::complex<double> s = 0.0;
    for (int i = 0; i < cells; ++i)
      s += phi[i] * std::polar(1.0, -2.0 * std::numbers::pi * i / cells);
    return std::arg(s);
  };
  double t = 0.0;
  while (t < 250.0) {
    solver.step(phi, v, dt);
    t += dt;
  }
  const double t0 = t;
  double last = phase(), travelled = 0.0;
  while (t < 300.0) {
    for (double s = 0.0; s < 0.15; s += dt) { // the pulse moves ~0.4 < L/2 between phases
      solver.step(phi, v, dt);
      t += dt;
    }
    double d = phase() - last;
    d -= 2.0 * std::numbers::pi * std::round(d / (2.0 * std::numbers::pi));
    travelled += d;
    last += d;
  }
  Pulse p;
  p.c = -travelled / (2.0 * std::numbers::pi / L * (t - t0));
  const std::vector<double> dphi = derivative(phi, L), dv = derivative(v, L);
  double qmin = 1e300, qmax = -1e300, res2 = 0.0, dv2 = 0.0;
  for (int i = 0; i < cells; ++i) {
    const double q = (v[i] - p.c) * phi[i] - dphi[i];
    qmin = std::min(qmin, q);
    qmax = std::max(qmax, q);
    p.q += q / cells;
    const double r = dv[i] - (1.0 - m.xi(phi[i]) * v[i]) / (v[i] - p.c);
    res2 += r * r;
    dv2 += dv[i] * dv[i];
  }
  p.q_spread = qmax - qmin;
  p.residual = std::sqrt(res2 / dv2);
  const auto [lo, hi] = std::minmax_element(phi.begin(), phi.end());
  p.phi_min = *lo;
  p.phi_max = *hi;
  const double v_lo = v[static_cast<std::size_t>(lo - phi.begin())];
  const double v_hi = v[static_cast<std::size_t>(hi - phi.begin())];
  p.c_6_15 = (p.phi_max * v_hi - p.phi_min * v_lo) / (p.phi_max - p.phi_min);
  std::printf("  PDE pulse on %d points: c = %.6f, q = %.6f (spread %.2e), phi from %.6f to "
              "%.6f; eq 6.14 residual rms %.2e of rms |v'|; eq 6.15 from the extremes: c = %.6f\n",
              cells, p.c, p.q, p.q_spread, p.phi_min, p.phi_max, p.residual, p.c_6_15);
  return p;
}

TEST(JammingWave, PulseGrownInThePDEIsATravellingWave) {
  const JammingModel m = mu1();
  const Pulse coarse = grow_pulse(m, 128), p = grow_pulse(m, 256);
  const auto fps = fixed_points(m, p.c, p.q);
  print(p.c, p.q, fps);
  EXPECT_LT(p.c, 0.0);                                       // against the flow (eq 6.15)
  EXPECT_LT(std::abs(p.c - coarse.c), 1e-3 * std::abs(p.c)); // resolved speed
  EXPECT_LT(p.q_spread, 5e-4 * p.q);                         // measured 1.2e-4 to 2.6e-4
  EXPECT_LT(p.residual, 0.5 * coarse.residual);              // shrinks with the grid
  EXPECT_LT(p.residual, 0.15);
  // Eq 6.15 in its exact two-point form, at the grid points of largest and smallest phi (where
  // phi' = 0 up to the grid: 3.3e-3 off on 128 points, 8e-4 on 256).
  EXPECT_LT(std::abs(p.c_6_15 - p.c), 2e-3 * std::abs(p.c));
  ASSERT_EQ(fps.size(), 3u);
  EXPECT_EQ(fps[0].type, FixedPointType::saddle);
  EXPECT_EQ(fps[2].type, FixedPointType::saddle);
  EXPECT_LT(std::abs(p.phi_max - fps[2].phi), 1e-3);
  EXPECT_GT(p.phi_min, fps[0].phi); // the rarefaction stays above the free-flow saddle
}

} // namespace
