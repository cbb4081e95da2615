// Streaming kernels: exact ballistic motion under the body force, then periodic wrapping.
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include "narrows/core/trig_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace narrows::mpcd {

namespace {

template <int D> void wrap_all(Fluid &f, const Box &box) {
  for (int k = 0; k < D; ++k) {
    double *x = f.x[k].data();
    const double L = box.length[k];
    const std::size_t n = f.size();
    for (std::size_t i = 0; i < n; ++i)
      x[i] = wrap_periodic(x[i], L);
  }
}

template <int D> void free_kernel(Fluid &f, const Box &box, double dt) {
  const std::size_t n = f.size();
  for (int k = 0; k < D; ++k) {
    double *x = f.x[k].data();
    const double *v = f.v[k].data();
    const double L = box.length[k];
    for (std::size_t i = 0; i < n; ++i)
      x[i] = wrap_periodic(x[i] + v[i] * dt, L);
  }
}

template <int D>
void constant_kernel(Fluid &f, const Box &box, double dt, const std::array<double, 3> &g) {
  const std::size_t n = f.size();
  for (int k = 0; k < D; ++k) {
    double *x = f.x[k].data();
    double *v = f.v[k].data();
    const double L = box.length[k];
    const double half_g_dt2 = 0.5 * g[k] * dt * dt, g_dt = g[k] * dt;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = wrap_periodic(x[i] + v[i] * dt + half_g_dt2, L);
      v[i] += g_dt;
    }
  }
}

// Arguments up to this size are reduced by three exact parts of pi/2 (below).
constexpr double reduced_limit = 0x1p19;

// sin and cos of x for |x| <= reduced_limit, without a branch (the loop over the particles
// vectorises): x = n pi/2 + r with n = round(2x/pi) and r by fdlibm's pi/2 in three parts and a
// tail (e_rem_pio2.c: 33 bits each, so n times each part is exact for |n| < 2^20), then fdlibm's
// k_sin.c and k_cos.c kernels on [-pi/4, pi/4] (minimax, error < 2^-58): within a few ulp of
// libm's.
inline void sincos_reduced(double x, double &sine, double &cosine) {
  constexpr double two_over_pi = 6.36619772367581382433e-01;
  constexpr double pio2_1 = 1.57079632673412561417e+00, pio2_2 = 6.07710050630396597660e-11,
                   pio2_3 = 2.02226624871116645580e-21, pio2_3t = 8.47842766036889956997e-32;
  const double n = std::nearbyint(x * two_over_pi);
  const double r = (((x - n * pio2_1) - n * pio2_2) - n * pio2_3) - n * pio2_3t;
  double s, c;
  trig::kernel_sincos(r, s, c);
  trig::to_quadrant(static_cast<unsigned>(static_cast<std::int64_t>(n) & 3), s, c, sine, cosine);
}

// The kick from sin and cos of theta0 and of phi (see sine_kick).
inline SineKick kick_of(double S, double C, double phi, double s, double c, double A, double dt) {
  // Each bracketed function by its Taylor series for |phi| < 0.1 (truncation below 1e-16
  // relative), where the closed form would lose digits to cancellation; both are computed and
  // one is selected (no branch: the divisions of the other cannot trap, phi = 0 divides 1).
  const double p2 = phi * phi;
  const bool series = std::abs(phi) < 0.1;
  const double sinc_s = 1.0 - p2 / 6.0 * (1.0 - p2 / 20.0 * (1.0 - p2 / 42.0 * (1.0 - p2 / 72.0)));
  const double c2_s =
      0.5 * (1.0 - p2 / 12.0 * (1.0 - p2 / 30.0 * (1.0 - p2 / 56.0 * (1.0 - p2 / 90.0))));
  const double c3_s = phi / 6.0 * (1.0 - p2 / 20.0 * (1.0 - p2 / 42.0 * (1.0 - p2 / 72.0)));
  const double q = series ? 1.0 : phi; // (the closed form's divisor)
  const double sinc_c = s / q, c1_c = (1.0 - c) / q, c2_c = c1_c / q, c3_c = (q - s) / (q * q);
  const double sinc = series ? sinc_s : sinc_c;
  const double c2 = series ? c2_s : c2_c;
  const double c1 = series ? phi * c2_s : c1_c;
  const double c3 = series ? c3_s : c3_c;
  // (The sums of two products fused explicitly: left to the compiler, which product is fused
  // differed between the vector loop and the scalar path.)
  return {A * dt * dt * std::fma(S, c2, C * c3), A * dt * std::fma(S, sinc, C * c1)};
}

// Kicks a batch at a time: a loop of fixed length with no branch, which vectorises whole (no
// remainder), so every lane takes the same instructions and a kick does not depend on where in
// a batch it sits (sine_kick puts its one in a batch of its own; not inlined, so that both run
// the same code; restrict, so that there is no scalar version for overlapping arrays).
constexpr std::size_t kick_batch = 64;
[[gnu::noinline]] void kick_batch_reduced(const double *__restrict theta0,
                                          const double *__restrict phi, double A, double dt,
                                          double *__restrict dx, double *__restrict dv) {
  for (std::size_t j = 0; j < kick_batch; ++j) {
    double S, C, s, c;
    sincos_reduced(theta0[j], S, C);
    sincos_reduced(phi[j], s, c);
    const SineKick k = kick_of(S, C, phi[j], s, c, A, dt);
    dx[j] = k.dx;
    dv[j] = k.dv;
  }
}

} // namespace

SineKick sine_kick(double theta0, double phi, double A, double dt) {
  // v_x(t) = v_x0 + A int_0^t sin(theta0 + phi s/dt) ds. With S = sin(theta0), C = cos(theta0):
  //   dv = A dt [S sin(phi)/phi + C (1 - cos phi)/phi]
  //   dx = A dt^2 [S (1 - cos phi)/phi^2 + C (phi - sin phi)/phi^2]
  if (std::abs(theta0) <= reduced_limit && std::abs(phi) <= reduced_limit) {
    alignas(64) double t[kick_batch] = {}, p[kick_batch] = {}, dx[kick_batch], dv[kick_batch];
    t[0] = theta0;
    p[0] = phi;
    kick_batch_reduced(t, p, A, dt, dx, dv);
    return {dx[0], dv[0]};
  }
  // (a speed no run reaches, or not finite: libm's reduction)
  return kick_of(std::sin(theta0), std::cos(theta0), phi, std::sin(phi), std::cos(phi), A, dt);
}

void stream_free(Fluid &fluid, const Box &box, double dt) {
  if (box.dim == 3)
    free_kernel<3>(fluid, box, dt);
  else
    free_kernel<2>(fluid, box, dt);
}

void stream_constant_force(Fluid &fluid, const Box &box, double dt,
                           const std::array<double, 3> &accel) {
  if (box.dim == 3)
    constant_kernel<3>(fluid, box, dt, accel);
  else
    constant_kernel<2>(fluid, box, dt, accel);
}

void stream_sine_force(Fluid &fluid, const Box &box, double dt, double amplitude) {
  const double k = 2.0 * std::numbers::pi / box.length[1];
  double *x = fluid.x[0].data(), *y = fluid.x[1].data();
  double *vx = fluid.v[0].data();
  const double *vy = fluid.v[1].data();
  const std::size_t n = fluid.size();
  // A batch at a time: its arguments (padded with zeros) all within reduced_limit (always,
  // but for speeds no run reaches), then its kicks in one vector loop; else one by one through
  // sine_kick. Either way each particle's kick is sine_kick's, bitwise.
  alignas(64) double theta0[kick_batch], phi[kick_batch], dx[kick_batch], dv[kick_batch];
  for (std::size_t i0 = 0; i0 < n; i0 += kick_batch) {
    const std::size_t m = std::min(kick_batch, n - i0);
    bool within = true;
    for (std::size_t j = 0; j < kick_batch; ++j) {
      theta0[j] = j < m ? k * y[i0 + j] : 0.0;
      phi[j] = j < m ? k * vy[i0 + j] * dt : 0.0;
      within &= (std::abs(theta0[j]) <= reduced_limit) & (std::abs(phi[j]) <= reduced_limit);
    }
    if (within) {
      kick_batch_reduced(theta0, phi, amplitude, dt, dx, dv);
    } else {
      for (std::size_t j = 0; j < m; ++j) {
        const SineKick kick = sine_kick(theta0[j], phi[j], amplitude, dt);
        dx[j] = kick.dx;
        dv[j] = kick.dv;
      }
    }
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t i = i0 + j;
      x[i] += vx[i] * dt + dx[j];
      vx[i] += dv[j];
      y[i] += vy[i] * dt;
    }
  }
  if (box.dim == 3) {
    double *z = fluid.x[2].data();
    const double *vz = fluid.v[2].data();
    for (std::size_t i = 0; i < n; ++i)
      z[i] += vz[i] * dt;
    wrap_all<3>(fluid, box);
  } else {
    wrap_all<2>(fluid, box);
  }
}

} // namespace narrows::mpcd
