// Streaming kernels: exact ballistic motion under the body force, then periodic wrapping.
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <cmath>
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

} // namespace

SineKick sine_kick(double theta0, double phi, double A, double dt) {
  // v_x(t) = v_x0 + A int_0^t sin(theta0 + phi s/dt) ds. With S = sin(theta0), C = cos(theta0):
  //   dv = A dt [S sin(phi)/phi + C (1 - cos phi)/phi]
  //   dx = A dt^2 [S (1 - cos phi)/phi^2 + C (phi - sin phi)/phi^2]
  // Each bracketed function is evaluated by its Taylor series for |phi| < 0.1 (truncation
  // below 1e-16 relative), where the closed form would lose digits to cancellation.
  const double S = std::sin(theta0), C = std::cos(theta0);
  double sinc, c1, c2, c3; // sin/phi, (1-cos)/phi, (1-cos)/phi^2, (phi-sin)/phi^2
  if (std::abs(phi) < 0.1) {
    const double p2 = phi * phi;
    sinc = 1.0 - p2 / 6.0 * (1.0 - p2 / 20.0 * (1.0 - p2 / 42.0 * (1.0 - p2 / 72.0)));
    c2 = 0.5 * (1.0 - p2 / 12.0 * (1.0 - p2 / 30.0 * (1.0 - p2 / 56.0 * (1.0 - p2 / 90.0))));
    c1 = phi * c2;
    c3 = phi / 6.0 * (1.0 - p2 / 20.0 * (1.0 - p2 / 42.0 * (1.0 - p2 / 72.0)));
  } else {
    const double s = std::sin(phi), c = std::cos(phi);
    sinc = s / phi;
    c1 = (1.0 - c) / phi;
    c2 = c1 / phi;
    c3 = (phi - s) / (phi * phi);
  }
  return {A * dt * dt * (S * c2 + C * c3), A * dt * (S * sinc + C * c1)};
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
  for (std::size_t i = 0; i < n; ++i) {
    const SineKick kick = sine_kick(k * y[i], k * vy[i] * dt, amplitude, dt);
    x[i] += vx[i] * dt + kick.dx;
    vx[i] += kick.dv;
    y[i] += vy[i] * dt;
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
