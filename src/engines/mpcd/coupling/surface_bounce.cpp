// Bounce-back of fluid particles at the surfaces of no-slip colloids (Kanehl (thesis) §4.2.1).
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace narrows::coupling {

using namespace narrows::colloids;

namespace {

// Halvings of the interval before a particle still inside a colloid is put on its surface
// without further flight (a particle trapped in a narrow gap).
constexpr int max_halvings = 20;

// Placed this far outside the surface (relative to the radius), so that it is not found inside
// again by rounding; and at least `rounding_gap` times the box's longest edge, since the point is
// stored as an absolute position: near x = 2e4 doubles are 3.6e-12 apart, more than 1e-12 of a
// radius 1.6, and a particle put on the surface of a colloid there was found inside it again
// (a packed channel 20000 long stopped at step 0). Boxes shorter than ~560 radii keep the relative
// gap, bitwise as before.
constexpr double surface_gap = 1e-12;
constexpr double rounding_gap = 8.0 * std::numeric_limits<double>::epsilon();

} // namespace

int NoSlipCoupling::leave_overlaps(const Colloids &c, std::size_t a, double *s) const {
  // The surface point s (relative to colloid a's centre) may lie inside a colloid b that a
  // overlaps, or beyond a wall a overlaps (spring contacts are soft). Then s moves to the
  // nearest point of the rim where the two surfaces meet (the circle where a's surface crosses b's
  // or the wall plane), a hair outside it: a point of a's surface outside both. Where three
  // overlap, the rim may lie inside a third: a few tries, then the caller's check refuses.
  const double ra = c.radius[a];
  const double hair = 1e-9 * ra;
  const auto &L = box_.length;
  for (int attempt = 0; attempt < 4; ++attempt) {
    double q[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < dim_; ++k) {
      q[k] = c.x[k][a] + s[k];
      if (!(k == 1 && box_.walls_y))
        q[k] = mpcd::wrap_periodic(q[k], L[k]);
    }
    double e[3] = {0.0, 0.0, 0.0}, t = 0.0, rho2 = 0.0;
    if (box_.walls_y && (q[1] < 0.0 || q[1] > L[1])) { // the rim on the wall plane
      t = (q[1] < 0.0 ? 0.0 : L[1]) - c.x[1][a];
      e[1] = t < 0.0 ? -1.0 : 1.0;
      t = std::abs(t);
    } else {
      const long b = lookup_.inside(c, q);
      if (b < 0)
        return attempt > 0 ? 1 : 0;
      double d2 = 0.0;
      for (int k = 0; k < dim_; ++k) {
        e[k] = c.x[k][static_cast<std::size_t>(b)] - c.x[k][a];
        if (!(k == 1 && box_.walls_y))
          e[k] = minimum_image(e[k], L[k]);
        d2 += e[k] * e[k];
      }
      const double d = std::sqrt(d2), rb = c.radius[static_cast<std::size_t>(b)];
      if (!(d > 0.0))
        return -1;
      for (int k = 0; k < dim_; ++k)
        e[k] /= d;
      t = (d2 + ra * ra - rb * rb) / (2.0 * d); // the rim's plane from a's centre along e
    }
    rho2 = ra * ra - t * t;
    if (!(rho2 > 0.0))
      return -1; // one inside the other
    // The direction of s across e (any, if s lies along e).
    double se = 0.0, w[3] = {0.0, 0.0, 0.0}, w2 = 0.0;
    for (int k = 0; k < dim_; ++k)
      se += s[k] * e[k];
    for (int k = 0; k < dim_; ++k) {
      w[k] = s[k] - se * e[k];
      w2 += w[k] * w[k];
    }
    if (!(w2 > 1e-24 * ra * ra)) {
      w[0] = -e[1], w[1] = e[0], w[2] = 0.0;
      if (dim_ == 3 && std::abs(e[2]) > 0.9)
        w[0] = 1.0, w[1] = 0.0, w[2] = 0.0;
      w2 = 0.0;
      for (int k = 0; k < dim_; ++k) {
        w[k] -= (w[0] * e[0] + w[1] * e[1] + w[2] * e[2]) * e[k];
        w2 += w[k] * w[k];
      }
    }
    const double rim = (std::sqrt(rho2) + hair) / std::sqrt(w2);
    for (int k = 0; k < dim_; ++k)
      s[k] = t * e[k] + rim * w[k];
  }
  return -1;
}

BounceStats NoSlipCoupling::bounce_back(mpcd::Fluid &fluid, Colloids &c,
                                        const FluidStream &stream) {
  const ScopedSeconds timed(seconds_);
  const ScopedSeconds stage(stage_seconds_[bounce]);
  BounceStats stats;
  const std::size_t n = fluid.size();
  batch_.dim = dim_;
  batch_.resize(0);
  batch_index_.clear();
  batch_hit_.clear();
  // First the particles in cells that list a colloid, without a branch on each (which of
  // them are is random: a branch would miss often), then which of those are inside one.
  candidates_.resize(n);
  candidate_cells_.resize(n);
  std::size_t listed = 0;
  std::uint32_t found[ColloidLookup::block];
  std::int32_t found_cell[ColloidLookup::block];
  for (std::size_t i0 = 0; i0 < n; i0 += ColloidLookup::block) {
    const std::size_t m = std::min(ColloidLookup::block, n - i0);
    const std::size_t k =
        lookup_.listed_block(fluid.x[0].data() + i0, fluid.x[1].data() + i0,
                             dim_ == 3 ? fluid.x[2].data() + i0 : nullptr, m, found, found_cell);
    for (std::size_t j = 0; j < k; ++j) {
      candidates_[listed + j] = i0 + found[j];
      candidate_cells_[listed + j] = found_cell[j];
    }
    listed += k;
  }
  for (std::size_t q = 0; q < listed; ++q) {
    const std::size_t i = candidates_[q];
    const double p[3] = {fluid.x[0][i], fluid.x[1][i], dim_ == 3 ? fluid.x[2][i] : 0.0};
    const long a = lookup_.inside_listed(c, p, candidate_cells_[q]); // (its cell, found above)
    if (a < 0)
      continue;
    batch_index_.push_back(i);
    batch_hit_.push_back(a);
  }
  const std::size_t m = batch_index_.size();
  stats.particles = m;
  batch_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    for (int k = 0; k < dim_; ++k) {
      batch_.x[k][j] = fluid.x[k][batch_index_[j]];
      batch_.v[k][j] = fluid.v[k][batch_index_[j]];
    }
    batch_.id[j] = fluid.id[batch_index_[j]];
  }
  // `active_` lists the batch rows still inside a colloid; each level halves the interval.
  active_.resize(m);
  for (std::size_t j = 0; j < m; ++j)
    active_[j] = j;
  kicks_.clear();
  const double two_pi_over_ly = 2.0 * std::numbers::pi / box_.length[1];
  const double absolute_gap =
      rounding_gap * std::max({box_.length[0], box_.length[1], dim_ == 3 ? box_.length[2] : 0.0});
  double T = params_.dt;
  level_.dim = dim_;
  for (int depth = 1; !active_.empty(); ++depth) {
    stats.deepest = depth;
    const bool last = depth > max_halvings;
    for (const std::size_t j : active_) {
      const auto a = static_cast<std::size_t>(batch_hit_[j]);
      double r[3] = {0.0, 0.0, 0.0}, vb[3] = {0.0, 0.0, 0.0}, g[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < dim_; ++k)
        g[k] = params_.fluid_accel[k];
      if (params_.sine_amplitude != 0.0)
        g[0] += params_.sine_amplitude * std::sin(two_pi_over_ly * batch_.x[1][j]);
      // Back half the interval in free flight under the body force (the last level: no
      // flight, the particle goes to the surface point nearest to where it is).
      const double h = last ? 0.0 : 0.5 * T;
      for (int k = 0; k < dim_; ++k) {
        vb[k] = batch_.v[k][j] - g[k] * h;
        r[k] = batch_.x[k][j] - batch_.v[k][j] * h + 0.5 * g[k] * h * h;
      }
      double d[3] = {0.0, 0.0, 0.0}, len2 = 0.0;
      for (int k = 0; k < dim_; ++k) {
        d[k] = r[k] - c.x[k][a];
        if (!(k == 1 && box_.walls_y))
          d[k] = minimum_image(d[k], box_.length[k]);
        len2 += d[k] * d[k];
      }
      if (!(len2 > 1e-24)) { // at the centre: leave along x
        d[0] = 1.0;
        d[1] = d[2] = 0.0;
        len2 = 1.0;
      }
      const double scale =
          std::max(c.radius[a] * (1.0 + surface_gap), c.radius[a] + absolute_gap) / std::sqrt(len2);
      double s[3] = {0.0, 0.0, 0.0}, u[3], dp[3];
      for (int k = 0; k < dim_; ++k)
        s[k] = d[k] * scale; // the surface point relative to the centre
      // Soft contacts overlap: a surface point inside a partner or beyond a wall goes to the
      // rim where the surfaces meet, and the particle stays there for the rest of the step (a
      // flight from the rim would only run into one of the two again, and a particle bounced
      // to and fro between two surfaces closing in gains energy).
      bool settled = false;
      if (params_.spring_contacts)
        settled = leave_overlaps(c, a, s) != 0;
      // The rigid-body velocity there: U + Omega x s.
      const double w[3] = {c.omega[0][a], c.omega[1][a], c.omega[2][a]};
      u[0] = c.v[0][a] + w[1] * s[2] - w[2] * s[1];
      u[1] = c.v[1][a] + w[2] * s[0] - w[0] * s[2];
      u[2] = (dim_ == 3 ? c.v[2][a] : 0.0) + w[0] * s[1] - w[1] * s[0];
      // With soft contacts a particle that stays on a surface for the rest of the step (on a
      // rim, or trapped after the last halving) takes the surface's velocity: bounced to and fro
      // between surfaces of vibrating contacts it would gain energy step after step. So does one
      // that is inside a colloid again after its first bounce of the step: trapped in a gap
      // between a colloid and a wall (or another colloid) that closes in, each further bounce
      // off the moving surface added 2|U| to its speed (to ~50 over 20 halvings, and the kicks
      // threw a pressed pyramid of disks apart).
      const bool stays = params_.spring_contacts && (settled || last || depth > 1);
      for (int k = 0; k < dim_; ++k) {
        const double v_new = stays ? u[k] : 2.0 * u[k] - vb[k];
        dp[k] = -(v_new - vb[k]); // what the colloid receives
        double x = c.x[k][a] + s[k];
        if (!(k == 1 && box_.walls_y))
          x = mpcd::wrap_periodic(x, box_.length[k]);
        else // a colloid touching a wall: its surface gap must not cross the wall
          x = std::min(std::max(x, 0.0), box_.length[1]);
        batch_.x[k][j] = x;
        batch_.v[k][j] = v_new;
      }
      add_impulse(a, s, dp);
      if (params_.implicit)
        kicks_.push_back({j, a, {s[0], s[1], s[2]}, stays ? 1.0 : 2.0});
      if (settled || stays)
        batch_hit_[j] = -1; // stays on the surface (or rim) for the rest of the step
    }
    if (last)
      break;
    if (params_.spring_contacts)
      active_.erase(std::remove_if(active_.begin(), active_.end(),
                                   [&](std::size_t j) { return batch_hit_[j] < 0; }),
                    active_.end());
    // Forward half the interval from the surface, walls and body force exact.
    level_.resize(active_.size());
    for (std::size_t q = 0; q < active_.size(); ++q)
      for (int k = 0; k < dim_; ++k) {
        level_.x[k][q] = batch_.x[k][active_[q]];
        level_.v[k][q] = batch_.v[k][active_[q]];
        level_.id[q] = batch_.id[active_[q]];
      }
    stream(level_, 0.5 * T);
    still_.clear();
    for (std::size_t q = 0; q < active_.size(); ++q) {
      const std::size_t j = active_[q];
      double p[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < dim_; ++k) {
        batch_.x[k][j] = level_.x[k][q];
        batch_.v[k][j] = level_.v[k][q];
        p[k] = level_.x[k][q];
      }
      const long a = lookup_.inside(c, p);
      if (a >= 0) {
        batch_hit_[j] = a;
        still_.push_back(j);
      }
    }
    active_.swap(still_);
    T *= 0.5;
  }
  // No fluid inside a colloid after the step (Kanehl (thesis) §4.2.1): checked for every particle
  // that was bounced, the others were outside already.
  for (std::size_t j = 0; j < m; ++j) {
    const double p[3] = {batch_.x[0][j], batch_.x[1][j], dim_ == 3 ? batch_.x[2][j] : 0.0};
    const long a = lookup_.inside(c, p);
    if (a >= 0) {
      std::ostringstream os;
      os.precision(17);
      os << "fluid particle id " << batch_.id[j] << " is inside colloid id " << c.id[a]
         << " after its bounce-back (trapped between colloids that overlap or touch a wall)";
      throw invariant_error(os.str());
    }
    for (int k = 0; k < dim_; ++k) {
      fluid.x[k][batch_index_[j]] = batch_.x[k][j];
      fluid.v[k][batch_index_[j]] = batch_.v[k][j];
    }
  }
  ghosts_.check_region(batch_);
  // Implicit exchange: the response of each bounced particle's velocity to the colloid's, at
  // the particle's final position (the lever of its correction). A bounce gives the colloid
  // f (v - U - Omega x s), d/dX = -f J(s): with the midpoint rule one bounce alone is then
  // exactly the elastic collision of the particle with the colloid (the explicit change gains
  // 2 (v - U)^2 / M of energy in each).
  double J[3][6];
  for (const Kick &k : kicks_) {
    double lever[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < dim_; ++d) {
      lever[d] = batch_.x[d][k.j] - c.x[d][k.row];
      if (!(d == 1 && box_.walls_y))
        lever[d] = minimum_image(lever[d], box_.length[d]);
    }
    surface_map(k.s.data(), k.f, J);
    add_response(k.row, J, lever);
  }
  apply_impulses(c, true);
  for (const Kick &k : kicks_) { // the fluid's share: G dX/2
    surface_map(k.s.data(), k.f, J);
    const double *h = &half_[k.row * dof_];
    for (int d = 0; d < dim_; ++d) {
      double dv = 0.0;
      for (int j = 0; j < dof_; ++j)
        dv += J[d][j] * h[j];
      fluid.v[d][batch_index_[k.j]] += dv;
    }
  }
  return stats;
}

} // namespace narrows::coupling
