// Event-driven rough hard spheres: collision rule and time-ordered events.
#include "narrows/colloids/hard_spheres.hpp"

#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <vector>

namespace narrows::colloids {

namespace {

void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The impulse dp that reverses the contact velocity U of a pair with reduced mass m and reduced
// moment of inertia i (eq 4.27): -2 m (U_n + U_t / (1 + m / i)), n the unit contact normal.
void reversing_impulse(const double U[3], const double n[3], double m, double i, double dp[3]) {
  const double un = dot(U, n);
  const double tangential = 1.0 / (1.0 + m / i);
  for (int k = 0; k < 3; ++k) {
    const double normal = un * n[k];
    dp[k] = -2.0 * m * (normal + (U[k] - normal) * tangential);
  }
}

} // namespace

double moment_of_inertia(const Colloids &c, std::size_t a) {
  const double r = c.radius[a];
  return (c.dim == 2 ? 0.5 : 0.4) * c.mass[a] * r * r;
}

void collide_rough(Colloids &c, std::size_t a, std::size_t b, const double d[3]) {
  const double ra = c.radius[a], rb = c.radius[b];
  const double ma = c.mass[a], mb = c.mass[b];
  const double ia = moment_of_inertia(c, a), ib = moment_of_inertia(c, b);
  double n[3] = {0.0, 0.0, 0.0}, du[3] = {0.0, 0.0, 0.0}, w[3], wxn[3];
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < c.dim; ++k) {
    n[k] = d[k] / len;
    du[k] = c.v[k][a] - c.v[k][b];
  }
  for (int k = 0; k < 3; ++k)
    w[k] = ra * c.omega[k][a] + rb * c.omega[k][b];
  cross(w, n, wxn);
  double U[3]; // eq 4.26 with d / R_ab = n at contact
  for (int k = 0; k < 3; ++k)
    U[k] = du[k] - wxn[k];
  const double m = ma * mb / (ma + mb);                     // eq 4.28
  const double i = ia * ib / (ra * ra * ib + rb * rb * ia); // eq 4.29
  double dp[3], nxdp[3];
  reversing_impulse(U, n, m, i, dp);
  cross(n, dp, nxdp);
  for (int k = 0; k < c.dim; ++k) { // eq 4.30-4.31
    c.v[k][a] += dp[k] / ma;
    c.v[k][b] -= dp[k] / mb;
  }
  for (int k = 0; k < 3; ++k) { // eq 4.32-4.33 (d / R_ab = n)
    c.omega[k][a] -= ra / ia * nxdp[k];
    c.omega[k][b] -= rb / ib * nxdp[k];
  }
}

void collide_rough_wall(Colloids &c, std::size_t a, int side) {
  // The wall is the partner b with infinite mass and inertia at rest: d = x_a - x_contact points
  // along n, the reduced mass is M_a and the reduced inertia I_a / R_a^2.
  const double r = c.radius[a], m = c.mass[a], ia = moment_of_inertia(c, a);
  const double n[3] = {0.0, static_cast<double>(side), 0.0};
  double w[3], wxn[3], U[3], dp[3], nxdp[3];
  for (int k = 0; k < 3; ++k)
    w[k] = r * c.omega[k][a];
  cross(w, n, wxn);
  for (int k = 0; k < 3; ++k)
    U[k] = (k < c.dim ? c.v[k][a] : 0.0) - wxn[k];
  reversing_impulse(U, n, m, ia / (r * r), dp);
  cross(n, dp, nxdp);
  for (int k = 0; k < c.dim; ++k)
    c.v[k][a] += dp[k] / m;
  for (int k = 0; k < 3; ++k)
    c.omega[k][a] -= r / ia * nxdp[k];
}

double kinetic_energy(const Colloids &c) {
  double e = 0.0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    for (int k = 0; k < c.dim; ++k)
      e += 0.5 * c.mass[a] * c.v[k][a] * c.v[k][a];
    const double i = moment_of_inertia(c, a);
    for (int k = 0; k < 3; ++k)
      e += 0.5 * i * c.omega[k][a] * c.omega[k][a];
  }
  return e;
}

namespace {

constexpr std::size_t wall_low = std::numeric_limits<std::size_t>::max();
constexpr std::size_t wall_high = wall_low - 1;

struct Event {
  double t;
  std::size_t a, b; // b: a colloid, or wall_low / wall_high
  std::uint64_t stamp_a, stamp_b;
  std::uint64_t id_a, id_b; // ties in a fixed order of the colloid ids (rows differ by rank)
  // Earliest first.
  bool operator>(const Event &o) const {
    if (t != o.t)
      return t > o.t;
    if (id_a != o.id_a)
      return id_a > o.id_a;
    return id_b > o.id_b;
  }
};

class EventQueue {
public:
  EventQueue(Colloids &c, const mpcd::Box &box, double dt, std::vector<std::uint8_t> *trusted,
             bool every_pair)
      : c_(c), box_(box), dt_(dt), t_(c.size(), 0.0), stamp_(c.size(), 0), trusted_(trusted),
        every_pair_(every_pair) {}

  // The position of colloid a at time t (not wrapped).
  double x_at(std::size_t a, int k, double t) const {
    return c_.x[k][a] + c_.v[k][a] * (t - t_[a]);
  }
  void move_to(std::size_t a, double t) {
    for (int k = 0; k < c_.dim; ++k)
      c_.x[k][a] = x_at(a, k, t);
    t_[a] = t;
  }

  // d = x_a - x_b at time t (minimum image along periodic axes); returns |d|^2.
  double separation_at(std::size_t a, std::size_t b, double t, double d[3]) const {
    double r2 = 0.0;
    d[0] = d[1] = d[2] = 0.0;
    for (int k = 0; k < c_.dim; ++k) {
      d[k] = x_at(a, k, t) - x_at(b, k, t);
      if (!(k == 1 && box_.walls_y))
        d[k] = minimum_image(d[k], box_.length[k]);
      r2 += d[k] * d[k];
    }
    return r2;
  }

  // Partners of a pair event within the step lie within reach_ of each other along every axis
  // at the start (their distance then less the sum of radii, covered at the relative speed,
  // which is below twice the fastest speed of the step so far): cells of the start positions,
  // at least reach_ wide along each axis, so that only the colloids of a's cell and its
  // neighbours need a prediction (along x alone, a 200-disk channel predicted three times as
  // many pairs). The events found are those of all pairs (the others would come after the
  // step, which push() drops), so the results are bitwise the same.
  void bin_start_positions() {
    const std::size_t n = c_.size();
    r_max_ = 0.0;
    v_max_ = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      r_max_ = std::max(r_max_, c_.radius[a]);
      v_max_ = std::max(v_max_, speed(a));
    }
    // Room for the fastest speed to double before the cells are too narrow.
    const double L = box_.length[0];
    margin_ = 1e-6 * (1.0 + L); // far above the rounding of positions and times
    reach_ = 2.0 * r_max_ + 4.0 * v_max_ * dt_ + margin_;
    // Cells per axis: a periodic axis needs three (a cell and two distinct neighbours) or is
    // one cell; the walls' axis needs one.
    binned_ = false;
    if (every_pair_)
      return;
    std::size_t cells = 1;
    for (int k = 0; k < 3; ++k) {
      cells_[k] = 1;
      if (k >= c_.dim)
        continue;
      const bool wall = k == 1 && box_.walls_y;
      const int fit = static_cast<int>(std::floor(box_.length[k] / reach_));
      if (fit >= 3 || (wall && fit >= 2))
        cells_[k] = fit;
      binned_ = binned_ || cells_[k] > 1;
      cells *= static_cast<std::size_t>(cells_[k]);
    }
    // A few colloids in a large box: coarser cells (still at least reach_ wide), at most ~8 a
    // colloid, not one per reach_ of an empty box.
    while (binned_ && cells > 8 * n + 64) {
      const int k = static_cast<int>(std::max_element(cells_, cells_ + 3) - cells_);
      const bool wall = k == 1 && box_.walls_y;
      cells /= static_cast<std::size_t>(cells_[k]);
      cells_[k] /= 2;
      if (cells_[k] < (wall ? 2 : 3))
        cells_[k] = 1;
      cells *= static_cast<std::size_t>(cells_[k]);
      binned_ = cells_[0] > 1 || cells_[1] > 1 || cells_[2] > 1;
    }
    if (!binned_)
      return; // every pair
    bin_of_.resize(n);
    first_.assign(cells + 1, 0);
    for (std::size_t a = 0; a < n; ++a) {
      std::size_t cell = 0;
      for (int k = c_.dim - 1; k >= 0; --k) {
        const double Lk = box_.length[k];
        const double x = k == 1 && box_.walls_y ? std::clamp(c_.x[k][a], 0.0, Lk)
                                                : mpcd::wrap_periodic(c_.x[k][a], Lk);
        const int i = std::min(static_cast<int>(x / Lk * cells_[k]), cells_[k] - 1);
        cell = cell * static_cast<std::size_t>(cells_[k]) + static_cast<std::size_t>(i);
      }
      bin_of_[a] = cell;
      ++first_[cell + 1];
    }
    for (std::size_t b = 0; b < cells; ++b)
      first_[b + 1] += first_[b];
    members_.resize(n);
    std::vector<std::size_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t a = 0; a < n; ++a)
      members_[fill[bin_of_[a]]++] = a;
  }
  double speed(std::size_t a) const {
    double v2 = 0.0;
    for (int k = 0; k < c_.dim; ++k)
      v2 += c_.v[k][a] * c_.v[k][a];
    return std::sqrt(v2);
  }
  // After a collision: the fastest speed so far; bins too narrow for it are given up.
  void sped(std::size_t a) {
    v_max_ = std::max(v_max_, speed(a));
    if (binned_ && 2.0 * r_max_ + 2.0 * v_max_ * dt_ + margin_ > reach_)
      binned_ = false;
  }

  // Every event of colloid a from time t on (eq 4.23-4.25; walls: the time to touch).
  void predict(std::size_t a, double t) {
    if (!binned_) {
      for (std::size_t b = 0; b < c_.size(); ++b)
        predict_pair(a, b, t);
    } else {
      // a's cell and its neighbours: along a periodic axis of 3 or more cells wrapped, along
      // the walls' axis those that exist, along an axis of one cell that one.
      int home[3];
      std::size_t rest = bin_of_[a];
      for (int k = 0; k < 3; ++k) {
        home[k] = static_cast<int>(rest % static_cast<std::size_t>(cells_[k]));
        rest /= static_cast<std::size_t>(cells_[k]);
      }
      int lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        const bool wall = k == 1 && box_.walls_y;
        lo[k] = cells_[k] == 1 ? 0 : wall ? std::max(home[k] - 1, 0) : home[k] - 1;
        hi[k] = cells_[k] == 1 ? 0 : wall ? std::min(home[k] + 1, cells_[k] - 1) : home[k] + 1;
      }
      for (int iz = lo[2]; iz <= hi[2]; ++iz)
        for (int iy = lo[1]; iy <= hi[1]; ++iy)
          for (int ix = lo[0]; ix <= hi[0]; ++ix) {
            const int wx = (ix + cells_[0]) % cells_[0], wy = (iy + cells_[1]) % cells_[1],
                      wz = (iz + cells_[2]) % cells_[2];
            const auto cell = static_cast<std::size_t>(wx + cells_[0] * (wy + cells_[1] * wz));
            for (std::size_t j = first_[cell]; j < first_[cell + 1]; ++j)
              predict_pair(a, members_[j], t);
          }
    }
    predict_walls(a, t);
  }
  // One copy of the code for both ways of predict() (inlined into each, the compiler could
  // contract a product and a sum into one rounding in one and not the other: other bits).
  [[gnu::noinline]] void predict_pair(std::size_t a, std::size_t b, double t) {
    {
      if (b == a)
        return;
      double d[3], du2 = 0.0, bij = 0.0;
      const double r2 = separation_at(a, b, t, d);
      for (int k = 0; k < c_.dim; ++k) {
        const double du = c_.v[k][a] - c_.v[k][b];
        du2 += du * du;
        bij += d[k] * du;
      }
      if (!(bij < 0.0))
        return; // not approaching
      const double rab = c_.radius[a] + c_.radius[b];
      const double kij = bij * bij - du2 * (r2 - rab * rab);
      if (!(kij > 0.0))
        return; // passing by
      const double tau = std::max(0.0, (-bij - std::sqrt(kij)) / du2);
      push(t + tau, a, b);
    }
  }
  void predict_walls(std::size_t a, double t) {
    if (box_.walls_y) {
      const double y = x_at(a, 1, t), vy = c_.v[1][a], r = c_.radius[a];
      if (vy < 0.0)
        push(t + std::max(0.0, (y - r) / -vy), a, wall_low);
      else if (vy > 0.0)
        push(t + std::max(0.0, (box_.length[1] - r - y) / vy), a, wall_high);
    }
  }

  HardSphereStats run() {
    HardSphereStats stats;
    bin_start_positions();
    for (std::size_t a = 0; a < c_.size(); ++a)
      predict(a, 0.0);
    // A bound on the events of one step, stale ones included: a physical step has a few
    // collisions per colloid, but a colloid of speed 1e300 (an edited checkpoint) between two
    // others or the walls collides ever more often and the step would never end (nor honour a
    // stop signal, which is asked for between steps).
    const std::uint64_t max_events = 1000000 + 1000 * static_cast<std::uint64_t>(c_.size());
    std::uint64_t events = 0;
    while (!queue_.empty() && queue_.top().t <= dt_) {
      if (++events > max_events)
        too_many_events(max_events, queue_.top().t);
      const Event e = queue_.top();
      queue_.pop();
      if (e.stamp_a != stamp_[e.a] || (e.b < wall_high && e.stamp_b != stamp_[e.b]))
        continue; // one of them collided since the prediction
      move_to(e.a, e.t);
      ++stamp_[e.a];
      if (e.b >= wall_high) {
        collide_rough_wall(c_, e.a, e.b == wall_low ? +1 : -1);
        sped(e.a);
        ++stats.wall_collisions;
      } else {
        move_to(e.b, e.t);
        ++stamp_[e.b];
        double d[3];
        separation_at(e.a, e.b, e.t, d);
        collide_rough(c_, e.a, e.b, d);
        sped(e.a);
        sped(e.b);
        ++stats.pair_collisions;
        if (trusted_ && (*trusted_)[e.a] != (*trusted_)[e.b]) // one may have missed a partner
          (*trusted_)[e.a] = (*trusted_)[e.b] = 0;
        predict(e.b, e.t);
      }
      predict(e.a, e.t);
    }
    for (std::size_t a = 0; a < c_.size(); ++a) {
      move_to(a, dt_);
      for (int k = 0; k < c_.dim; ++k)
        if (!(k == 1 && box_.walls_y))
          c_.x[k][a] = mpcd::wrap_periodic(c_.x[k][a], box_.length[k]);
    }
    return stats;
  }

private:
  [[noreturn]] void too_many_events(std::uint64_t max_events, double t) const {
    std::size_t fastest = 0;
    double v_fastest = -1.0;
    for (std::size_t a = 0; a < c_.size(); ++a) {
      const double v = std::hypot(c_.v[0][a], c_.v[1][a], c_.dim == 3 ? c_.v[2][a] : 0.0);
      if (!(v <= v_fastest)) { // (hypot: no overflow to inf at 1e300)
        v_fastest = v;
        fastest = a;
      }
    }
    char line[400];
    std::snprintf(line, sizeof line,
                  "hard contacts: more than %llu collision events in one step (at t = %.3g of "
                  "dt = %.3g) among %zu colloids; the fastest, id %llu, moves at %.3g; the step "
                  "cannot end (allowed: colloid speeds far below a radius per step)",
                  static_cast<unsigned long long>(max_events), t, dt_, c_.size(),
                  static_cast<unsigned long long>(c_.id[fastest]), v_fastest);
    throw invariant_error(line);
  }
  void push(double t, std::size_t a, std::size_t b) {
    if (t > dt_)
      return;
    const bool wall = b >= wall_high;
    queue_.push({t, a, b, stamp_[a], wall ? 0 : stamp_[b], c_.id[a],
                 wall ? ~0ull - (b == wall_low) : c_.id[b]});
  }

  Colloids &c_;
  mpcd::Box box_;
  double dt_;
  std::vector<double> t_;            // per colloid: the time its position refers to
  std::vector<std::uint64_t> stamp_; // per colloid: collisions so far (stale events differ)
  std::vector<std::uint8_t> *trusted_;
  bool every_pair_;
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> queue_;
  // Cells of the start positions (bin_start_positions); not binned_: every pair is predicted.
  bool binned_ = false;
  int cells_[3] = {1, 1, 1};
  double reach_ = 0.0, r_max_ = 0.0, v_max_ = 0.0, margin_ = 0.0;
  std::vector<std::size_t> bin_of_;
  std::vector<std::size_t> first_, members_;
};

} // namespace

HardSphereStats advance_hard_spheres(Colloids &c, const mpcd::Box &box, double dt,
                                     std::vector<std::uint8_t> *trusted, bool every_pair) {
  EventQueue q(c, box, dt, trusted, every_pair);
  return q.run();
}

} // namespace narrows::colloids
