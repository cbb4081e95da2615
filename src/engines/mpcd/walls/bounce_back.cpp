// Bounce-back and specular walls for the streaming step (Tabatabaei (2008) eq 3.9-3.13, derived for
// a force with components along and across the wall: at the hit the velocity is reversed and
// the rest of the step is flown under the force again).
#include "narrows/engines/mpcd/walls/bounce_back.hpp"

#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <cmath>
#include <limits>

namespace narrows::walls {

double time_to_wall(double h, double u, double a) {
  constexpr double never = std::numeric_limits<double>::infinity();
  const double disc = u * u - 2.0 * a * h;
  if (disc < 0.0)
    return never; // turns back before reaching the wall
  const double root = std::sqrt(disc);
  if (u <= 0.0) {
    // Approaching: the first root, t = 2h / (sqrt(disc) - u), free of cancellation.
    const double den = root - u;
    if (den == 0.0) // u = 0 and a h = 0: on the wall at rest, leaves now only if pulled out
      return (h == 0.0 && a < 0.0) ? 0.0 : never;
    return 2.0 * h / den;
  }
  // Moving away: comes back only if pulled toward the wall.
  return a < 0.0 ? (u + root) / -a : never;
}

namespace {

// One particle's state during the step.
template <int D> struct Flight {
  double x[3], v[3];
  void fly(double t, const std::array<double, 3> &g) {
    for (int k = 0; k < D; ++k) {
      x[k] += (v[k] + 0.5 * g[k] * t) * t;
      v[k] += g[k] * t;
    }
  }
};

// True when the flight over dt under acceleration gy stays within [0, L] (the parabola's
// extremum is checked when it falls inside the step).
inline bool stays_inside(double y, double vy, double gy, double dt, double L) {
  const double end = y + (vy + 0.5 * gy * dt) * dt;
  if (!(end >= 0.0 && end <= L))
    return false;
  if (gy == 0.0)
    return true;
  const double t_ext = -vy / gy;
  if (t_ext <= 0.0 || t_ext >= dt)
    return true;
  const double ext = y + 0.5 * vy * t_ext;
  return ext >= 0.0 && ext <= L;
}

template <int D, bool Slip>
void channel_kernel(mpcd::Fluid &f, const mpcd::Box &box, double dt,
                    const std::array<double, 3> &g) {
  const double L = box.length[1];
  const std::size_t n = f.size();
  double *X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};
  double *V[3] = {f.v[0].data(), f.v[1].data(), D == 3 ? f.v[2].data() : nullptr};
  for (std::size_t i = 0; i < n; ++i) {
    Flight<D> p;
    for (int k = 0; k < D; ++k) {
      p.x[k] = X[k][i];
      p.v[k] = V[k][i];
    }
    if (stays_inside(p.x[1], p.v[1], g[1], dt, L)) {
      p.fly(dt, g);
    } else {
      double left = dt;
      for (int hit = 0;; ++hit) {
        const double t_low = time_to_wall(p.x[1], p.v[1], g[1]);
        const double t_high = time_to_wall(L - p.x[1], -p.v[1], -g[1]);
        const bool high = t_high < t_low;
        const double t = high ? t_high : t_low;
        if (!(t < left) || hit == max_hits_per_step) {
          p.fly(left, g);
          break;
        }
        p.fly(t, g);
        p.x[1] = high ? L : 0.0;
        if constexpr (Slip) {
          p.v[1] = -p.v[1];
        } else {
          for (int k = 0; k < D; ++k)
            p.v[k] = -p.v[k];
        }
        left -= t;
      }
      // Round-off of the last flight may leave y a few ulp outside.
      p.x[1] = std::fmin(std::fmax(p.x[1], 0.0), L);
    }
    X[0][i] = mpcd::wrap_periodic(p.x[0], box.length[0]);
    X[1][i] = p.x[1];
    V[0][i] = p.v[0];
    V[1][i] = p.v[1];
    if constexpr (D == 3) {
      X[2][i] = mpcd::wrap_periodic(p.x[2], box.length[2]);
      V[2][i] = p.v[2];
    }
  }
}

} // namespace

void stream_channel(mpcd::Fluid &fluid, const mpcd::Box &box, double dt,
                    const std::array<double, 3> &accel, bool slip) {
  if (box.dim == 3)
    slip ? channel_kernel<3, true>(fluid, box, dt, accel)
         : channel_kernel<3, false>(fluid, box, dt, accel);
  else
    slip ? channel_kernel<2, true>(fluid, box, dt, accel)
         : channel_kernel<2, false>(fluid, box, dt, accel);
}

} // namespace narrows::walls
