// The Ladd-Frenkel colloid of the FHP lattice gas (see lattice/fhp_colloid.hpp).
#include "narrows/engines/lgca/fhp_colloid.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/lgca/fhp_observables.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

namespace narrows::lgca {

namespace {

constexpr double sqrt3_2 = 0.8660254037844386;
// c_k = (a[k] / 2, b[k] sqrt(3) / 2)
constexpr int a_units[6] = {2, 1, -1, -2, -1, 1};
constexpr int b_units[6] = {0, 1, 1, 0, -1, -1};

double cx(int k) { return 0.5 * a_units[k]; }
double cy(int k) { return sqrt3_2 * b_units[k]; }

// v wrapped into [0, l).
double wrap(double v, double l) {
  v = std::fmod(v, l);
  if (v < 0.0)
    v += l;
  return v >= l ? v - l : v;
}

// The global indices lo..hi wrapped into [0, n), sorted, each once.
std::vector<int> wrapped_range(int lo, int hi, int n) {
  std::vector<int> out;
  if (hi - lo + 1 >= n) {
    for (int i = 0; i < n; ++i)
      out.push_back(i);
    return out;
  }
  for (int i = lo; i <= hi; ++i)
    out.push_back(((i % n) + n) % n);
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace

FhpColloid::FhpColloid(const ColloidParams &params, const FhpLattice &lattice)
    : params_(params), size_x_(lattice.size_x()), size_y_(lattice.size_y()) {
  if (!(params.radius > 0.0) || !(params.mass > 0.0))
    throw input_error("colloid.radius and colloid.mass must be > 0");
  lx_ = size_x_;
  ly_ = size_y_ * sqrt3_2;
  if (!(2.0 * params.radius < std::min(lx_, ly_)))
    throw input_error("colloid.radius = " + std::to_string(params.radius) +
                      ": the diameter is not smaller than the box (" + std::to_string(size_x_) +
                      " x " + std::to_string(ly_) + "); allowed: radius < " +
                      std::to_string(0.5 * std::min(lx_, ly_)));
  if (!params.held && lattice.has_solids())
    throw input_error("colloid.held = false with lattice walls or obstacles is not available "
                      "(the disc has no contact rule with solids); allowed: held = true, or no "
                      "walls and obstacles");
  // 1/sqrt(3) is the covering radius of the triangular lattice: a smaller moving disc would
  // cover no site at some positions and coast through the gas untouched.
  if (!params.held && params.radius < 0.5774)
    throw input_error("colloid.radius = " + std::to_string(params.radius) +
                      " with colloid.held = false covers no site at some positions; allowed: "
                      "radius >= 0.5774 (1/sqrt(3)) for a moving disc");
  x_ = wrap(params.x, lx_);
  y_ = wrap(params.y, ly_);
  update_geometry(true);
  if (inside_.empty())
    throw input_error("colloid.radius = " + std::to_string(params.radius) +
                      " covers no site; allowed: a radius that covers at least one site");
  inertia_ = 0.5 * params.mass * params.radius * params.radius;
  momentum_ = {std::llround(2.0 * params.mass * params.vx),
               std::llround(params.mass * params.vy / sqrt3_2)};
}

void FhpColloid::set_state(const MomentumUnits &p, double omega,
                           const std::array<double, 2> &position, double angle) {
  momentum_ = p;
  omega_ = omega;
  x_ = wrap(position[0], lx_);
  y_ = wrap(position[1], ly_);
  angle_ = angle;
  update_geometry(true);
}

void FhpColloid::update_geometry(bool force) {
  if (!force && margin_ > 0.0) {
    const double dx = std::remainder(x_ - x0_, lx_), dy = std::remainder(y_ - y0_, ly_);
    // every site is farther than margin_ from the circle of the last check: none has crossed
    if (std::sqrt(dx * dx + dy * dy) < margin_ - 1e-9)
      return;
  }
  ++checks_;
  const double R = params_.radius;
  // The bounding box of the disc plus one ring: every site within R, every neighbour of one.
  const std::vector<int> cols = wrapped_range(static_cast<int>(std::floor(x_ - R - 0.5)) - 1,
                                              static_cast<int>(std::ceil(x_ + R)) + 1, size_x_);
  const std::vector<int> rows =
      wrapped_range(static_cast<int>(std::floor((y_ - R) / sqrt3_2)) - 1,
                    static_cast<int>(std::ceil((y_ + R) / sqrt3_2)) + 1, size_y_);
  const std::size_t nc = cols.size(), nr = rows.size();
  // Offsets from the centre (nearest image): one remainder per column and per row; a site is
  // then x offset + half a spacing on odd rows.
  std::vector<double> ox(nc), oy(nr);
  for (std::size_t i = 0; i < nc; ++i)
    ox[i] = std::remainder(cols[i] - x_, lx_);
  for (std::size_t j = 0; j < nr; ++j)
    oy[j] = std::remainder(rows[j] * sqrt3_2 - y_, ly_);
  const auto dist2 = [&](std::size_t i, std::size_t j) {
    double dx = ox[i] + 0.5 * (rows[j] % 2);
    if (dx > 0.5 * lx_)
      dx -= lx_;
    return dx * dx + oy[j] * oy[j];
  };
  // Sites outside the box are more than R + 1.7 from the centre: a move below 0.5 cannot
  // bring them in.
  double margin = 0.5;
  std::vector<Site> inside;
  std::vector<std::uint8_t> in(nr * nc);
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i) {
      const double d2 = dist2(i, j);
      const bool s = d2 <= R * R;
      in[j * nc + i] = s;
      // |d - R| < margin needs |d^2 - R^2| = |d - R| (d + R) < margin (2 R + margin)
      if (std::abs(d2 - R * R) < margin * (2.0 * R + margin))
        margin = std::min(margin, std::abs(std::sqrt(d2) - R));
      if (s)
        inside.push_back({cols[i], rows[j]});
    }
  x0_ = x_;
  y0_ = y_;
  margin_ = margin;
  const auto same = [](const std::vector<Site> &a, const std::vector<Site> &b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](Site p, Site q) {
             return p.x == q.x && p.y == q.y;
           });
  };
  if (!force && same(inside, inside_))
    return;
  ++rebuilds_;
  inside_ = std::move(inside);
  links_.clear();
  sites_.clear();
  // Where a global column / row sits in the box (-1: outside, not covered).
  col_at_.assign(static_cast<std::size_t>(size_x_), -1);
  row_at_.assign(static_cast<std::size_t>(size_y_), -1);
  for (std::size_t i = 0; i < nc; ++i)
    col_at_[cols[i]] = static_cast<int>(i);
  for (std::size_t j = 0; j < nr; ++j)
    row_at_[rows[j]] = static_cast<int>(j);
  const auto covered = [&](int x, int y) {
    const int i = col_at_[x], j = row_at_[y];
    return i >= 0 && j >= 0 && in[static_cast<std::size_t>(j) * nc + i] != 0;
  };
  struct Raw {
    Site a, b;
    int k;
    double mx, my;
  };
  std::vector<Raw> raw;
  // Only sites within one spacing of the circle have a neighbour on the other side.
  const double near_in = R > 1.01 ? (R - 1.01) * (R - 1.01) : -1.0,
               near_out = (R + 1.01) * (R + 1.01);
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i) {
      const double d2 = dist2(i, j);
      if (d2 < near_in || d2 > near_out)
        continue;
      const int x = cols[i], y = rows[j], o = y % 2;
      const bool s = in[j * nc + i] != 0;
      const int nx[3] = {x + 1, x + o, x - 1 + o};
      const int ny[3] = {y, y + 1, y + 1};
      for (int k = 0; k < 3; ++k) {
        const int xb = (nx[k] + size_x_) % size_x_, yb = ny[k] % size_y_;
        if (covered(xb, yb) == s)
          continue;
        raw.push_back(
            {{x, y}, {xb, yb}, k, x + 0.5 * o + 0.5 * cx(k), (y + 0.5 * b_units[k]) * sqrt3_2});
        sites_.push_back({x, y});
        sites_.push_back({xb, yb});
      }
    }
  const auto before = [](Site p, Site q) { return p.y != q.y ? p.y < q.y : p.x < q.x; };
  std::sort(sites_.begin(), sites_.end(), before);
  sites_.erase(std::unique(sites_.begin(), sites_.end(),
                           [](Site p, Site q) { return p.x == q.x && p.y == q.y; }),
               sites_.end());
  const auto index = [&](Site s) {
    return static_cast<int>(std::lower_bound(sites_.begin(), sites_.end(), s, before) -
                            sites_.begin());
  };
  for (const Raw &r : raw)
    links_.push_back({index(r.a), index(r.b), r.k, r.mx, r.my});
  patch_.assign(sites_.size(), 0);
}

std::array<double, 2> FhpColloid::velocity() const {
  return {0.5 * static_cast<double>(momentum_[0]) / params_.mass,
          sqrt3_2 * static_cast<double>(momentum_[1]) / params_.mass};
}

namespace {

// Momentum (units) and particle count of the gas on the given sites this rank owns, summed
// over the ranks.
std::array<std::int64_t, 3> gas_on(const FhpLattice &lattice, const auto &sites) {
  std::array<std::int64_t, 3> s{0, 0, 0};
  const int first = lattice.first_column(), n = lattice.local_columns();
  for (const auto &p : sites) {
    const int x = p.x - first;
    if (x < 0 || x >= n)
      continue;
    const unsigned state = lattice.row(p.y)[x];
    for (int k = 0; k < 6; ++k)
      if ((state >> k) & 1u) {
        s[0] += a_units[k];
        s[1] += b_units[k];
      }
    s[2] += std::popcount(state);
  }
  if (lattice.slabs().ranks() > 1)
    MPI_Allreduce(MPI_IN_PLACE, s.data(), 3, MPI_INT64_T, MPI_SUM, lattice.comm());
  return s;
}

} // namespace

std::array<double, 2> FhpColloid::composite_velocity(const FhpLattice &lattice) const {
  const auto g = gas_on(lattice, inside_);
  const double m = params_.mass + static_cast<double>(g[2]);
  return {0.5 * static_cast<double>(momentum_[0] + g[0]) / m,
          sqrt3_2 * static_cast<double>(momentum_[1] + g[1]) / m};
}

double FhpColloid::composite_mass(const FhpLattice &lattice) const {
  return params_.mass + static_cast<double>(gas_on(lattice, inside_)[2]);
}

std::array<double, 2> FhpColloid::centre_of_mass_velocity(const FhpLattice &lattice) const {
  const MomentumUnits f = fluid_momentum(lattice);
  const double m = params_.mass + static_cast<double>(total_mass(lattice));
  return {0.5 * static_cast<double>(f[0] + momentum_[0]) / m,
          sqrt3_2 * static_cast<double>(f[1] + momentum_[1]) / m};
}

void FhpColloid::apply(FhpLattice &lattice) {
  // The end sites of the boundary links on every rank: owners give their state, others 0.
  const int first = lattice.first_column(), ncols = lattice.local_columns();
  const auto owned = [&](const Site &s) { return s.x >= first && s.x < first + ncols; };
  for (std::size_t i = 0; i < sites_.size(); ++i)
    patch_[i] = owned(sites_[i]) ? lattice.row(sites_[i].y)[sites_[i].x - first] : 0;
  if (lattice.slabs().ranks() > 1)
    MPI_Allreduce(MPI_IN_PLACE, patch_.data(), static_cast<int>(patch_.size()), MPI_UINT8_T,
                  MPI_BOR, lattice.comm());

  const auto u = velocity();
  const auto step = static_cast<std::uint64_t>(lattice.time() + 1);
  MomentumUnits dp{0, 0};
  double torque = 0.0;
  for (std::size_t n = 0; n < links_.size(); ++n) {
    const Link &l = links_[n];
    std::uint8_t &sa = patch_[l.a];
    std::uint8_t &sb = patch_[l.b];
    const unsigned ba = (sa >> l.k) & 1u, bb = (sb >> (l.k + 3)) & 1u;
    if (ba == bb)
      continue; // (0,0) and (1,1): reflection and crossing are the same
    const double rx = std::remainder(l.mx - x_, lx_), ry = std::remainder(l.my - y_, ly_);
    const double vx = u[0] - omega_ * ry, vy = u[1] + omega_ * rx;
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
    torque += sign * (rx * cy(l.k) - ry * cx(l.k));
  }
  for (std::size_t i = 0; i < sites_.size(); ++i)
    if (owned(sites_[i]))
      lattice.row(sites_[i].y)[sites_[i].x - first] = patch_[i];
  momentum_[0] += dp[0];
  momentum_[1] += dp[1];
  omega_ += torque / inertia_;
  if (params_.held)
    return;
  // The disc moves with its new velocity; the gas on both sides needs no transfer.
  const auto v = velocity();
  x_ = wrap(x_ + v[0], lx_);
  y_ = wrap(y_ + v[1], ly_);
  angle_ += omega_;
  update_geometry(false);
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

} // namespace narrows::lgca
