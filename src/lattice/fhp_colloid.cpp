// The Ladd-Frenkel colloid of the FHP lattice gas (see lattice/fhp_colloid.hpp).
#include "narrows/lattice/fhp_colloid.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/lattice/fhp_observables.hpp"

#include <bit>
#include <cmath>
#include <string>

namespace narrows::lattice {

namespace {

constexpr double sqrt3_2 = 0.8660254037844386;
// c_k = (a[k] / 2, b[k] sqrt(3) / 2)
constexpr int a_units[6] = {2, 1, -1, -2, -1, 1};
constexpr int b_units[6] = {0, 1, 1, 0, -1, -1};

double cx(int k) { return 0.5 * a_units[k]; }
double cy(int k) { return sqrt3_2 * b_units[k]; }

} // namespace

FhpColloid::FhpColloid(const ColloidParams &params, const FhpLattice &lattice) : params_(params) {
  if (lattice.slabs().ranks() > 1)
    throw input_error("[colloid] runs on 1 rank only in this version (the boundary links of a "
                      "disc across a slab edge are not exchanged); got " +
                      std::to_string(lattice.slabs().ranks()) + " ranks; allowed: 1 rank");
  if (!params.held)
    throw input_error("colloid.held = false (a moving disc) is not available in this version; "
                      "allowed: true (the held colloid of seed 002 §4.3)");
  if (!(params.radius > 0.0) || !(params.mass > 0.0))
    throw input_error("colloid.radius and colloid.mass must be > 0");
  const int X = lattice.size_x(), Y = lattice.size_y();
  const double lx = X, ly = Y * sqrt3_2;
  const auto rel = [&](double px, double py) {
    return std::array<double, 2>{std::remainder(px - params.x, lx),
                                 std::remainder(py - params.y, ly)};
  };
  const auto inside = [&](int x, int y) {
    const auto r = rel(x + 0.5 * (y % 2), y * sqrt3_2);
    return r[0] * r[0] + r[1] * r[1] <= params.radius * params.radius;
  };
  for (int y = 0; y < Y; ++y)
    for (int x = 0; x < X; ++x) {
      const bool in = inside(x, y);
      inside_sites_ += in;
      if (in)
        inside_.push_back({x, y});
      const int o = y % 2;
      const int nx[3] = {x + 1, x + o, x - 1 + o};
      const int ny[3] = {y, y + 1, y + 1};
      for (int k = 0; k < 3; ++k) {
        const int xb = (nx[k] + X) % X, yb = ny[k] % Y;
        if (inside(xb, yb) == in)
          continue;
        const auto r = rel(x + 0.5 * o + 0.5 * cx(k), (y + 0.5 * b_units[k]) * sqrt3_2);
        links_.push_back({x, y, xb, yb, k, r[0], r[1]});
      }
    }
  if (inside_sites_ == 0)
    throw input_error("colloid.radius = " + std::to_string(params.radius) +
                      " covers no site; allowed: a radius that covers at least one site");
  inertia_ = 0.5 * params.mass * params.radius * params.radius;
  momentum_ = {std::llround(2.0 * params.mass * params.vx),
               std::llround(params.mass * params.vy / sqrt3_2)};
}

std::array<double, 2> FhpColloid::velocity() const {
  return {0.5 * static_cast<double>(momentum_[0]) / params_.mass,
          sqrt3_2 * static_cast<double>(momentum_[1]) / params_.mass};
}

std::array<double, 2> FhpColloid::composite_velocity(const FhpLattice &lattice) const {
  std::int64_t pa = momentum_[0], pb = momentum_[1], n = 0;
  for (const auto &s : inside_) {
    const unsigned state = lattice.row(s[1])[s[0]];
    for (int k = 0; k < 6; ++k)
      if ((state >> k) & 1u) {
        pa += a_units[k];
        pb += b_units[k];
      }
    n += std::popcount(state);
  }
  const double m = params_.mass + static_cast<double>(n);
  return {0.5 * static_cast<double>(pa) / m, sqrt3_2 * static_cast<double>(pb) / m};
}

double FhpColloid::composite_mass(const FhpLattice &lattice) const {
  std::int64_t n = 0;
  for (const auto &s : inside_)
    n += std::popcount(static_cast<unsigned>(lattice.row(s[1])[s[0]]));
  return params_.mass + static_cast<double>(n);
}

std::array<double, 2> FhpColloid::centre_of_mass_velocity(const FhpLattice &lattice) const {
  const MomentumUnits f = fluid_momentum(lattice);
  const double m = params_.mass + static_cast<double>(total_mass(lattice));
  return {0.5 * static_cast<double>(f[0] + momentum_[0]) / m,
          sqrt3_2 * static_cast<double>(f[1] + momentum_[1]) / m};
}

void FhpColloid::apply(FhpLattice &lattice) {
  const auto u = velocity();
  const auto step = static_cast<std::uint64_t>(lattice.time() + 1);
  MomentumUnits dp{0, 0};
  double torque = 0.0;
  for (std::size_t n = 0; n < links_.size(); ++n) {
    const Link &l = links_[n];
    std::uint8_t &sa = lattice.row(l.ya)[l.xa];
    std::uint8_t &sb = lattice.row(l.yb)[l.xb];
    const unsigned ba = (sa >> l.k) & 1u, bb = (sb >> (l.k + 3)) & 1u;
    if (ba == bb)
      continue; // (0,0) and (1,1): reflection and crossing are the same
    const double vx = u[0] - omega_ * l.ry, vy = u[1] + omega_ * l.rx;
    const double xk = cx(l.k) * vx + cy(l.k) * vy;
    // x > 0: the lone particle moves with the wall and crosses with probability p (eq 27)
    const double x = ba != 0 ? xk : -xk;
    if (x > 0.0) {
      const double p = 2.0 * x / ((x + 0.5) * (x + 0.5));
      const auto r = rng::draw(params_.seed_for_rules, rng::Purpose::lgca_colloid, step, n);
      if (rng::open01(r[0]) < p)
        continue;
    }
    // reflection: exchange the slots (they differ, so flip both bits)
    sa = static_cast<std::uint8_t>(sa ^ (1u << l.k));
    sb = static_cast<std::uint8_t>(sb ^ (1u << (l.k + 3)));
    const int sign = ba != 0 ? 2 : -2; // momentum the colloid receives, in units of c_k
    dp[0] += sign * a_units[l.k];
    dp[1] += sign * b_units[l.k];
    torque += sign * (l.rx * cy(l.k) - l.ry * cx(l.k));
  }
  momentum_[0] += dp[0];
  momentum_[1] += dp[1];
  omega_ += torque / inertia_;
}

MomentumUnits fluid_momentum(const FhpLattice &lattice) {
  std::int64_t p[2] = {0, 0};
  for (int y = 0; y < lattice.size_y(); ++y) {
    const std::uint8_t *r = lattice.row(y);
    for (int x = 0; x < lattice.local_columns(); ++x)
      for (int k = 0; k < 6; ++k)
        if ((r[x] >> k) & 1u) {
          p[0] += a_units[k];
          p[1] += b_units[k];
        }
  }
  std::int64_t total[2] = {0, 0};
  MPI_Allreduce(p, total, 2, MPI_INT64_T, MPI_SUM, lattice.comm());
  return {total[0], total[1]};
}

} // namespace narrows::lattice
