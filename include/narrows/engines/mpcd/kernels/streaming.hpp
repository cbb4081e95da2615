// Streaming of fluid particles over one collision step, exact for the supported body forces,
// followed by periodic wrapping.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <array>
#include <cmath>

namespace narrows::mpcd {

// Back into [0, L). One subtraction almost always suffices; fmod handles the rest.
inline double wrap_periodic(double x, double L) {
  if (x >= L) {
    x -= L;
    if (x >= L)
      x = std::fmod(x, L);
  } else if (x < 0.0) {
    x += L;
    if (x < 0.0)
      x = std::fmod(x, L) + L;
    if (x >= L) // -tiny + L rounds to L
      x = 0.0;
  }
  return x;
}

// Free flight: x += v dt.
void stream_free(Fluid &fluid, const Box &box, double dt);

// Constant acceleration g: x += v dt + g dt^2/2, v += g dt.
void stream_constant_force(Fluid &fluid, const Box &box, double dt,
                           const std::array<double, 3> &accel);

// Kolmogorov forcing a_x = A sin(2 pi y / L_y): y moves freely, so v_x and x follow in closed
// form; the small-argument limits use series so the result is accurate for any v_y.
void stream_sine_force(Fluid &fluid, const Box &box, double dt, double amplitude);

// The closed-form displacement and velocity change along x for one particle (exposed for
// tests): theta0 = k y0, phi = k v_y dt, k = 2 pi / L_y.
struct SineKick {
  double dx; // displacement beyond v_x dt
  double dv; // change of v_x
};
SineKick sine_kick(double theta0, double phi, double amplitude, double dt);

} // namespace narrows::mpcd
