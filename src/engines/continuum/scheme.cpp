// MUSCL-TVD + Rusanov + SSP-RK2 finite volumes (see continuum/scheme.hpp).
#include "narrows/engines/continuum/scheme.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::continuum {

namespace {

double minmod(double a, double b) {
  if (a * b <= 0.0)
    return 0.0;
  return std::abs(a) < std::abs(b) ? a : b;
}

// Monotonised central: minmod(2a, (a + b) / 2, 2b).
double mc(double a, double b) {
  if (a * b <= 0.0)
    return 0.0;
  const double s = a > 0.0 ? 1.0 : -1.0;
  return s * std::min({2.0 * std::abs(a), 0.5 * std::abs(a + b), 2.0 * std::abs(b)});
}

} // namespace

double stable_dt(double max_speed, double dx, double diffusion, double cfl) {
  const double rate = max_speed / dx + 2.0 * diffusion / (dx * dx);
  return rate > 0.0 ? cfl / rate : 1e300;
}

Scheme::Scheme(const Flux &flux, const Grid &grid, double diffusion,
               scene::ContinuumLimiter limiter)
    : flux_(flux), grid_(grid), diffusion_(diffusion), limiter_(limiter) {
  const std::size_t n = static_cast<std::size_t>(grid.cells);
  ext_.resize(n + 4);
  slope_.resize(n + 4);
  face_.resize(n + 1);
  k_.resize(n);
  u1_.resize(n);
}

void Scheme::rate(const std::vector<double> &u, std::vector<double> &out) {
  const std::size_t n = u.size();
  // Cells 0..n-1 are ext_[2..n+1]; two ghost cells on each side.
  std::copy(u.begin(), u.end(), ext_.begin() + 2);
  if (grid_.periodic) {
    ext_[0] = u[n - 2];
    ext_[1] = u[n - 1];
    ext_[n + 2] = u[0];
    ext_[n + 3] = u[1];
  } else {
    ext_[0] = ext_[1] = grid_.left;
    ext_[n + 2] = ext_[n + 3] = grid_.right;
  }
  // Limited slopes of ext_[1..n+2] (the cells on both sides of every face).
  const bool use_mc = limiter_ == scene::ContinuumLimiter::mc;
  for (std::size_t j = 1; j <= n + 2; ++j) {
    const double a = ext_[j] - ext_[j - 1], b = ext_[j + 1] - ext_[j];
    slope_[j] = use_mc ? mc(a, b) : minmod(a, b);
  }
  // Face i sits between cells i-1 and i (ext_[i+1] and ext_[i+2]).
  for (std::size_t i = 0; i <= n; ++i) {
    const double ul = ext_[i + 1] + 0.5 * slope_[i + 1];
    const double ur = ext_[i + 2] - 0.5 * slope_[i + 2];
    const double a = std::max(std::abs(flux_.speed(ul)), std::abs(flux_.speed(ur)));
    face_[i] = 0.5 * (flux_(ul) + flux_(ur)) - 0.5 * a * (ur - ul);
  }
  const double inv_dx = 1.0 / grid_.dx, d = diffusion_ * inv_dx * inv_dx;
  for (std::size_t i = 0; i < n; ++i)
    out[i] =
        -(face_[i + 1] - face_[i]) * inv_dx + d * (ext_[i + 3] - 2.0 * ext_[i + 2] + ext_[i + 1]);
}

void Scheme::step(std::vector<double> &u, double dt) {
  const std::size_t n = u.size();
  rate(u, k_);
  for (std::size_t i = 0; i < n; ++i)
    u1_[i] = u[i] + dt * k_[i];
  rate(u1_, k_);
  for (std::size_t i = 0; i < n; ++i)
    u[i] = 0.5 * u[i] + 0.5 * (u1_[i] + dt * k_[i]);
}

} // namespace narrows::continuum
