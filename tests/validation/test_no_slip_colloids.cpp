// Issue 20 acceptance 3: the no-slip coupling (Kanehl (thesis) §4.2.1) puts the fluid at the
// colloid's rigid-body velocity at its surface.
//
// (a) A colloid held fixed in a Poiseuille flow: the time-averaged fluid velocity on lines
//     through its centre (along and across the channel) extrapolates to zero at its surface.
// (b) A free colloid at the centre of the shear of a Kolmogorov flow spins at Omega_z = -gdot/2,
//     gdot = du_x/dy of the fluid measured in the same run.
//
// Both use MPC-AT+a (the thesis' rule; SRD and AT-a do not conserve angular momentum, which
// changes the torque on a rotating body: Götze et al. (2007)).
#include "narrows/engines/mpcd/simulation.hpp"

#include "fluid_scene.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace narrows;

namespace {

double mean(const std::vector<double> &a) {
  double m = 0.0;
  for (double x : a)
    m += x / static_cast<double>(a.size());
  return m;
}

double standard_error(const std::vector<double> &a) {
  const double m = mean(a);
  double var = 0.0;
  for (double x : a)
    var += (x - m) * (x - m) / static_cast<double>(a.size() - 1);
  return std::sqrt(var / static_cast<double>(a.size()));
}

double minimum_image(double d, double L) { return d - L * std::round(d / L); }

// Least-squares fit of u = c0 + c1 s + c2 s^2; returns {c0, c1} (value and slope at s = 0).
std::array<double, 2> fit_quadratic(const std::vector<double> &s, const std::vector<double> &u) {
  double A[3][3] = {}, b[3] = {};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double p[3] = {1.0, s[i], s[i] * s[i]};
    for (int r = 0; r < 3; ++r) {
      b[r] += p[r] * u[i];
      for (int c = 0; c < 3; ++c)
        A[r][c] += p[r] * p[c];
    }
  }
  for (int k = 0; k < 3; ++k) // Gauss elimination (A is symmetric positive definite)
    for (int r = k + 1; r < 3; ++r) {
      const double f = A[r][k] / A[k][k];
      for (int c = k; c < 3; ++c)
        A[r][c] -= f * A[k][c];
      b[r] -= f * b[k];
    }
  double x[3];
  for (int r = 2; r >= 0; --r) {
    double t = b[r];
    for (int c = r + 1; c < 3; ++c)
      t -= A[r][c] * x[c];
    x[r] = t / A[r][r];
  }
  return {x[0], x[1]};
}

} // namespace

// (a) Poiseuille channel 48 x 24 (walls at y = 0, 24), AT+a, n = 10, dt = 0.1, g = 0.006; a disc
// of radius 4 at the centre. It is held by its mass, 1e13 fluid masses: the drag it takes
// (~10 per unit time) moves it by ~2e-5 over the run, and every stage of the coupling is the one
// a free colloid goes through (bounce-back at U + Omega x r, ghosts, impulses to the colloid);
// resetting its velocity each step through colloids() would hold it too, but would hide the
// impulses' effect on the next step.
// Six profiles of u_x, binned (width 0.25) in the distance s from a surface, averaged over the
// run: along the centre line on either side of the disc and across the channel between the
// disc and each wall (the four lines through the centre, in wedges of half-angle 20 deg), and
// the two walls half a box away. Each is fitted with a quadratic on 0 < s < 2 and extrapolated
// to s = 0. u0 is the centre-line velocity half a box away from the disc. Blocks of 1000 steps
// (100 time units, >> the momentum relaxation time of a gap, 8^2/(pi^2 nu) ~ 10) give the
// standard errors; 30 of them (10 gave b_s = 0.18 +- 0.024, too wide an error for the 0.25 bound
// below at this b_s: the implicit exchange changed the realisation, not the physics, of a disc this
// heavy). Cost: ~14 s.
TEST(NoSlipColloid, FixedDiscInPoiseuilleFlowHasZeroFluidVelocityAtItsSurface) {
  const double Lx = 48.0, Ly = 24.0, R = 4.0, g = 0.006;
  scene::Scene s =
      validation::fluid_scene(2, scene::Collision::at_a, 10.0, 0.1, 0.0, {Lx, Ly, 0.0}, 11);
  s.walls = scene::Walls{};
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {g, 0.0, 0.0}, 0.0};
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.contacts = scene::ColloidContacts::hard;
  c.radius = R;
  c.mass = 1e13;
  c.placement = scene::ColloidPlacement::list;
  c.positions = {{Lx / 2, Ly / 2, 0.0}};
  c.count = 1;
  s.colloids = c;
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  const double xc = Lx / 2, yc = Ly / 2;
  const int warmup = 2000, blocks = 30, block_steps = 1000, every = 2;
  const double bin = 0.25, reach = 2.0, wedge = std::tan(20.0 * std::numbers::pi / 180.0);
  const int nbins = static_cast<int>(reach / bin);
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  // Profiles: 0 left (x < xc), 1 right, 2 below (y < yc), 3 above; 4: u0 on the centre line.
  std::vector<std::vector<double>> block_intercept(6), block_slope(6), block_u0(1);
  for (int b = 0; b < blocks; ++b) {
    std::vector<std::vector<double>> sum(6, std::vector<double>(nbins, 0.0)),
        cnt(6, std::vector<double>(nbins, 0.0));
    double u0_sum = 0.0, u0_cnt = 0.0;
    for (int i = 0; i < block_steps; ++i) {
      sim.advance();
      if (i % every != 0)
        continue;
      const auto &f = sim.fluid();
      for (std::size_t j = 0; j < f.size(); ++j) {
        const double dx = minimum_image(f.x[0][j] - xc, Lx), dy = f.x[1][j] - yc;
        const double u = f.v[0][j];
        if (std::abs(dy) < 0.5 && std::abs(dx) > Lx / 2 - 1.0) { // centre line, far away
          u0_sum += u;
          u0_cnt += 1.0;
        }
        if (std::abs(dx) > Lx / 2 - 4.0) { // the walls, far from the disc
          const double sw = std::min(f.x[1][j], Ly - f.x[1][j]);
          if (sw > 0.0 && sw < reach) {
            const int k = static_cast<int>(sw / bin);
            sum[f.x[1][j] < yc ? 4 : 5][k] += u;
            cnt[f.x[1][j] < yc ? 4 : 5][k] += 1.0;
          }
        }
        // Wedges of half-angle 20 deg around the four directions of the lines.
        const double r = std::hypot(dx, dy), sd = r - R;
        if (!(sd > 0.0 && sd < reach))
          continue;
        int p = -1;
        if (std::abs(dy) < wedge * std::abs(dx))
          p = dx < 0 ? 0 : 1;
        else if (std::abs(dx) < wedge * std::abs(dy))
          p = dy < 0 ? 2 : 3;
        if (p < 0)
          continue;
        const int k = static_cast<int>(sd / bin);
        sum[p][k] += u;
        cnt[p][k] += 1.0;
      }
    }
    for (int p = 0; p < 6; ++p) {
      std::vector<double> sc, uc;
      for (int k = 0; k < nbins; ++k) {
        sc.push_back((k + 0.5) * bin);
        uc.push_back(sum[p][k] / cnt[p][k]);
      }
      const auto fit = fit_quadratic(sc, uc);
      block_intercept[p].push_back(fit[0]);
      block_slope[p].push_back(fit[1]);
    }
    block_u0[0].push_back(u0_sum / u0_cnt);
  }
  const double u0 = mean(block_u0[0]);
  const auto &col = sim.colloids();
  const double moved = std::hypot(col.x[0][0] - xc, col.x[1][0] - yc);
  std::printf("u0 = %.4f +- %.4f (centre line, x = xc + L/2); disc moved %.2g\n", u0,
              standard_error(block_u0[0]), moved);
  const char *names[6] = {"upstream",       "downstream",     "wall gap below",
                          "wall gap above", "wall y = 0 far", "wall y = L far"};
  for (int p = 0; p < 6; ++p) {
    const double u_s = mean(block_intercept[p]), err = standard_error(block_intercept[p]);
    const double slope = mean(block_slope[p]);
    std::printf("u_x at the surface, %s: %.5f +- %.5f = (%.2f +- %.2f) %% of u0, slope %.4f, "
                "slip length %.3f\n",
                names[p], u_s, err, 100 * u_s / u0, 100 * err / u0, slope, u_s / slope);
  }
  // Pairs of profiles, per block: up/downstream (u_x is the normal velocity there: a permeable
  // disc would give both the same sign), and the two gaps (u_x is the tangential velocity).
  const auto pair = [&](int p, const std::vector<std::vector<double>> &v) {
    std::vector<double> r;
    for (int b = 0; b < blocks; ++b)
      r.push_back(0.5 * (v[p][b] + v[p + 1][b]));
    return r;
  };
  const auto normal = pair(0, block_intercept), gap = pair(2, block_intercept);
  const auto gap_slope = pair(2, block_slope), wall = pair(4, block_intercept),
             wall_slope = pair(4, block_slope);
  const double un = mean(normal), un_err = standard_error(normal);
  const double ut = mean(gap), ut_err = standard_error(gap);
  const double bs = ut / mean(gap_slope);
  const double bs_err =
      std::abs(bs) * std::hypot(ut_err / ut, standard_error(gap_slope) / mean(gap_slope));
  const double bw = mean(wall) / mean(wall_slope);
  std::printf("normal velocity at the surface (up/downstream): (%.2f +- %.2f) %% of u0\n",
              100 * un / u0, 100 * un_err / u0);
  std::printf("tangential velocity at the surface (gaps): (%.2f +- %.2f) %% of u0, shear there "
              "%.4f = %.1f u0/L_y; slip length %.3f +- %.3f cells (walls: %.3f)\n",
              100 * ut / u0, 100 * ut_err / u0, mean(gap_slope), mean(gap_slope) * Ly / u0, bs,
              bs_err, bw);
  // No flow through the disc: |u_n| at the surface below 5 % of u0, by more than 2 standard
  // errors (measured: ~1 % +- 1 %).
  EXPECT_LT(std::abs(un) + 2.0 * un_err, 0.05 * u0);
  // No slip: the extrapolated tangential velocity is a slip length b_s = u_t/(du_t/ds) times the
  // shear at the surface. The planar no-slip walls of this fluid (virtual particles at rest) have
  // b_s = 0.1-0.2 cells (README; here the far walls, printed); the disc must do as well: |b_s|
  // < 0.25 cells by more than 3 standard errors (measured ~0.15 +- 0.03). Two-sided: a negative
  // b_s (fluid at the surface running against the flow, e.g. a surface velocity of the wrong
  // sign) is no more no-slip than a positive one. A disc that let the
  // fluid slip (specular reflection, or no ghosts) has b_s ~ R. In this geometry the gaps are
  // narrow (8 cells) and the shear at the disc is ~ 24 u0/L_y, so u_t is ~10 % of u0 although
  // b_s is that of the walls; the 5 % of the acceptance is reached where the shear at
  // the surface is below 0.5 u0 / b_s.
  EXPECT_LT(std::abs(bs) + 3.0 * bs_err, 0.25);
  EXPECT_GT(ut_err, 0.0);
  EXPECT_GT(u0, 0.1); // a flow to measure against
  EXPECT_LT(moved, 1e-4);
}

// (b) Kolmogorov flow a_x = A sin(k y), k = 2 pi/L_y, in a periodic 12 x 40 box, MPC-AT+a,
// n = 10, dt = 0.01 (the thesis'), A = 0.065; one free disc (radius a = 2, density-matched)
// starts at y = L_y/2, where u_x = 0 and the shear is largest. Theory (2D Stokes, exact for a
// torque-free disc by the reciprocal theorem): it spins at half the ambient vorticity averaged
// over its area, Omega_z = (1/2) <omega>_disc; for omega = omega_0 cos(k y) that is (1/2)
// omega_0 2 J1(ka)/(ka) = 0.988 (1/2) omega_0 at ka = 0.31. Small corrections left out: the body
// force the disc does not feel (a torque (ka)^2/8 ~ 1 % of the viscous one), inertia
// (Re_p = gdot a^2/nu = 0.14).
// The ambient shear is the one the disc sees, measured in the same run: the fluid velocity
// averaged along x, as a function of the height x = y - y_c above the disc's centre, fitted on
// a + 1/2 < x < L_y - a - 1/2 (the band of the disc left out, the rest of the box one interval
// around the periodic y) with u(x) = c0 + c1 sin(k x) + c2 cos(k x) + c3 x: outside the band
// the x-averaged Stokes flow is exactly the forced sine plus a uniform shear c3 (the disc row,
// stiffer than the fluid it replaces, takes up less of the velocity change; the box is
// periodic, so the rest shears more). The ambient vorticity at the disc is -(c1 k + c3).
// The far-field mode amplitude U (sin(k y) of the fluid away from the disc) is not that shear:
// with L_x = 12 (a disc every 3 diameters) it underestimates it by ~7 % (same run:
// Omega/(U k/2) = 1.070 +- 0.024 against 1.003 +- 0.023 here), which an earlier version of this
// test took for a spin excess.
// Statistics: Omega_z fluctuates with <Omega^2> = kT/I = 0.004 and decorrelates in
// I/zeta_r = a^2/(8 nu) ~ 0.15; blocks of 20 time units (2000 steps) are independent; the ratio
// and its error come from per-block sums (ratio estimator), ~0.10 per block.
//
// Measured with this estimator (issue 20, acceptance 3b): dt = 0.01, a = 2: 1.003 +- 0.023
// (20 blocks), 0.993 +- 0.019 (40 blocks), 0.982 +- 0.017 (50 blocks); with the batched
// Gaussians of the MPC-AT+a noise (another realisation) 0.996 +- 0.021 (50 blocks), and of the
// ghosts too 1.042 +- 0.019 (64 blocks); with the ghosts as sums per cut cell (exact in
// distribution, another realisation) 1.002 +- 0.0200 (64 blocks: a block scatter of 0.16, so
// the error bound below was missed by a hair; 80 blocks since, the test below). At half the thesis'
// time step the disc does spin too fast: dt = 0.005 (A doubled, U ~ 0.8): a = 2: 1.216 +- 0.050, a
// = 4 (L_y = 80, L_x = 32): 1.059 +- 0.049; with no ghost particles (bounce-back alone) the
// far-field estimate at dt = 0.005 is as high (1.25 +- 0.09), and bouncing back along the
// particle's own path instead of onto the nearest surface point as well (1.20 +- 0.03), so it is
// neither the ghosts' nor the radial move's doing; the cause is not found (an effect of a mean free
// path dt sqrt(kT) << a that grows as dt falls).
namespace {

struct SpinResult {
  double ratio, error; // Omega_z / ((1/2) <omega>_disc), one standard error
};

SpinResult spin_in_kolmogorov_flow(int blocks) {
  const double Lx = 12.0, Ly = 40.0, A = 0.065, a = 2.0;
  scene::Scene s =
      validation::fluid_scene(2, scene::Collision::at_a, 10.0, 0.01, 0.0, {Lx, Ly, 0.0}, 5);
  s.body_force = scene::BodyForce{scene::ForceKind::sine, {0.0, 0.0, 0.0}, A};
  scene::Colloids c;
  c.coupling = scene::ColloidCoupling::no_slip;
  c.radius = a;
  c.placement = scene::ColloidPlacement::list;
  c.positions = {{Lx / 2, Ly / 2, 0.0}};
  c.count = 1;
  s.colloids = c;
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  const double k = 2.0 * std::numbers::pi / Ly;
  const double disc_average = 2.0 * std::cyl_bessel_j(1.0, k * a) / (k * a);
  const int warmup = 2000, block_steps = 2000, every_u = 10;
  const double bin = 0.25, edge = a + 0.5;
  const int bins = static_cast<int>(Ly / bin);
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  // Per block b: a_b = Omega_b E_b, b_b = E_b^2 with Omega_b the block's mean spin and E_b the
  // expected one; the ratio is sum a / sum b, its error that of a ratio estimator.
  std::vector<double> block_a, block_b;
  for (int b = 0; b < blocks; ++b) {
    double spin = 0.0;
    std::vector<double> u_sum(bins, 0.0), count(bins, 0.0);
    for (int i = 0; i < block_steps; ++i) {
      sim.advance();
      const auto &col = sim.colloids();
      spin += col.omega[2][0] / block_steps;
      if (i % every_u != 0)
        continue;
      const auto &f = sim.fluid();
      for (std::size_t j = 0; j < f.size(); ++j) {
        double x = f.x[1][j] - col.x[1][0];
        x -= Ly * std::floor(x / Ly);
        const int q = std::min(bins - 1, static_cast<int>(x / bin));
        u_sum[q] += f.v[0][j];
        count[q] += 1.0;
      }
    }
    Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    for (int q = 0; q < bins; ++q) {
      const double x = (q + 0.5) * bin;
      if (x < edge || x > Ly - edge || count[q] == 0.0)
        continue;
      const Eigen::Vector4d phi(1.0, std::sin(k * x), std::cos(k * x), x);
      M += count[q] * phi * phi.transpose();
      rhs += u_sum[q] * phi;
    }
    const Eigen::Vector4d fit = M.ldlt().solve(rhs);
    const double expected = -0.5 * (fit[1] * k * disc_average + fit[3]);
    block_a.push_back(spin * expected);
    block_b.push_back(expected * expected);
    std::printf("block %2d: Omega %.4f, expected %.4f (sine %.4f, uniform %.5f), y_c %.2f\n", b,
                spin, expected, -0.5 * fit[1] * k, -0.5 * fit[3], sim.colloids().x[1][0]);
  }
  double sa = 0.0, sb = 0.0;
  for (int b = 0; b < blocks; ++b) {
    sa += block_a[b];
    sb += block_b[b];
  }
  const double ratio = sa / sb;
  double d2 = 0.0;
  for (int b = 0; b < blocks; ++b)
    d2 += (block_a[b] - ratio * block_b[b]) * (block_a[b] - ratio * block_b[b]);
  const double ratio_err = std::sqrt(d2 * blocks / (blocks - 1.0)) / sb;
  std::printf("Omega_z / ((1/2) <omega>_disc) = %.4f +- %.4f over %d blocks (disc average of "
              "the sine's vorticity %.4f)\n",
              ratio, ratio_err, blocks, disc_average);
  return {ratio, ratio_err};
}

} // namespace

// Acceptance 3b (issue 20): within 5 % of half the ambient vorticity, with a standard error
// small enough that 5 % is 2.5 of them (80 blocks of ~0.12-0.16 scatter: ~0.013-0.018; ~30 s).
TEST(NoSlipColloid, FreeDiscInKolmogorovFlowSpinsAtHalfTheShearRate) {
  // 120 blocks: with 80 the error bar was 0.0215 in one realisation, above the 0.02 that
  // lets the 5 % bound bite.
  const SpinResult r = spin_in_kolmogorov_flow(120);
  EXPECT_NEAR(r.ratio, 1.0, 0.05);
  EXPECT_LT(r.error, 0.02);
}
