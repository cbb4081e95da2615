// Bounce-back and specular walls for the streaming step (Tabatabaei (2008) eq 3.9-3.13, derived for
// a force with components along and across the wall: at the hit the velocity is reversed and
// the rest of the step is flown under the force again).
#include "narrows/engines/mpcd/walls/bounce_back.hpp"

#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// 1 when the flight over dt under acceleration gy stays within [0, L] (the parabola's
// extremum is checked when it falls inside the step; Pulled: gy != 0). Without branches, so
// that fly_block's loop vectorises; the plain path uses it too.
template <bool Pulled>
inline int stays_inside(double y, double vy, double gy, double dt, double L) {
  const double end = y + (vy + 0.5 * gy * dt) * dt;
  int ok = (end >= 0.0) & (end <= L);
  if constexpr (Pulled) {
    const double t_ext = -vy / gy;
    const double ext = y + 0.5 * vy * t_ext;
    ok &= (t_ext <= 0.0) | (t_ext >= dt) | ((ext >= 0.0) & (ext <= L));
  }
  return ok;
}

// One particle's whole step, hits and all (the plain path).
template <int D, bool Slip>
void channel_one(double *const *X, double *const *V, std::size_t i, const mpcd::Box &box, double dt,
                 const std::array<double, 3> &g) {
  const double L = box.length[1];
  Flight<D> p;
  for (int k = 0; k < D; ++k) {
    p.x[k] = X[k][i];
    p.v[k] = V[k][i];
  }
  if (g[1] != 0.0 ? stays_inside<true>(p.x[1], p.v[1], g[1], dt, L)
                  : stays_inside<false>(p.x[1], p.v[1], g[1], dt, L)) {
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

// wrap_periodic's common case without a branch: x within a box length of the box, wrapped
// into [0, L); `rare` is set otherwise (fmod needed, or -tiny + L rounded to L, or not finite).
inline double wrap_near(double x, double L, int &rare) {
  double y = x >= L ? x - L : x; // (two selects: a nested one does not vectorise in 3D)
  y = x < 0.0 ? x + L : y;
  rare |= 1 - ((y >= 0.0) & (y < L));
  return y;
}

// The free flight of m particles that stay inside the channel (and within a box length along
// the periodic axes), in a loop without branches that vectorises; the others are left as they
// were and flagged. Returns whether any was. (Distinct arrays: restrict spares the vectoriser
// its alias checks, too many in 3D.)
template <int D, bool Pulled>
int fly_block(double *__restrict x, double *__restrict y, double *__restrict z,
              double *__restrict vx, double *__restrict vy, double *__restrict vz,
              std::int32_t *__restrict flagged, std::size_t m, const mpcd::Box &box, double dt,
              const std::array<double, 3> &g) {
  const double L = box.length[1], Lx = box.length[0], Lz = box.length[2];
  const double gx = g[0], gy = g[1], gz = g[2];
  int any = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const int ok = stays_inside<Pulled>(y[i], vy[i], gy, dt, L);
    const double end = y[i] + (vy[i] + 0.5 * gy * dt) * dt; // (as Flight::fly's y)
    // Flight::fly(dt, g)
    int rare = 0;
    const double nx = wrap_near(x[i] + (vx[i] + 0.5 * gx * dt) * dt, Lx, rare);
    const double nvx = vx[i] + gx * dt, nvy = vy[i] + gy * dt;
    double nz = 0.0, nvz = 0.0;
    if constexpr (D == 3) {
      nz = wrap_near(z[i] + (vz[i] + 0.5 * gz * dt) * dt, Lz, rare);
      nvz = vz[i] + gz * dt;
    }
    const int flag = (1 - ok) | rare;
    flagged[i] = flag;
    any |= flag;
    x[i] = flag ? x[i] : nx;
    y[i] = flag ? y[i] : end;
    vx[i] = flag ? vx[i] : nvx;
    vy[i] = flag ? vy[i] : nvy;
    if constexpr (D == 3) {
      z[i] = flag ? z[i] : nz;
      vz[i] = flag ? vz[i] : nvz;
    }
  }
  return any;
}

// A block at a time: the particles that hit no wall flown together (fly_block), then the
// flagged ones one by one with their hits.
template <int D, bool Slip, bool Pulled>
void channel_kernel(mpcd::Fluid &f, const mpcd::Box &box, double dt,
                    const std::array<double, 3> &g) {
  const std::size_t n = f.size();
  double *const X[3] = {f.x[0].data(), f.x[1].data(), D == 3 ? f.x[2].data() : nullptr};
  double *const V[3] = {f.v[0].data(), f.v[1].data(), D == 3 ? f.v[2].data() : nullptr};
  constexpr std::size_t block = 256;
  std::int32_t flagged[block];
  for (std::size_t i0 = 0; i0 < n; i0 += block) {
    const std::size_t m = std::min(block, n - i0);
    const int any =
        fly_block<D, Pulled>(X[0] + i0, X[1] + i0, D == 3 ? X[2] + i0 : nullptr, V[0] + i0,
                             V[1] + i0, D == 3 ? V[2] + i0 : nullptr, flagged, m, box, dt, g);
    if (any)
      for (std::size_t j = 0; j < m; ++j)
        if (flagged[j])
          channel_one<D, Slip>(X, V, i0 + j, box, dt, g);
  }
}

template <int D, bool Slip>
void channel_kernel(mpcd::Fluid &f, const mpcd::Box &box, double dt,
                    const std::array<double, 3> &g) {
  if (g[1] != 0.0)
    channel_kernel<D, Slip, true>(f, box, dt, g);
  else
    channel_kernel<D, Slip, false>(f, box, dt, g);
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
