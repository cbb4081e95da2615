// Dense packings grown from points with the spring contacts and no fluid (Kanehl (thesis) §6.1).
#include "narrows/colloids/packing.hpp"

#include "narrows/colloids/colloid_pairs.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/colloids/springs.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace narrows::colloids {

namespace {

// The draws of the packing: placement "random" keys its tries (seed, attempt, index) with
// attempts below 2^40 (and 2^40 + attempt); the packing uses 3 * 2^40 + 2 j and + 2 j + 1 for
// its start (j = 0) and its j-th shake, beyond both.
constexpr std::uint64_t packing_draw = 3ull << 40;

template <int D, bool WallsY> double deepest(const Colloids &c, const mpcd::Box &box) {
  CellList cells;
  std::vector<int> cell_of;
  std::vector<std::uint32_t> partners;
  double r_max = 0.0;
  for (const double r : c.radius)
    r_max = std::max(r_max, r);
  double worst = 0.0;
  if (c.size() > 1) {
    cells.size_for(box, 2.0 * r_max);
    for_each_colloid_pair<D, WallsY>(
        cells, cell_of, partners, c, [&](std::size_t a, const std::vector<std::uint32_t> &near) {
          const double xa[3] = {c.x[0][a], c.x[1][a], D == 3 ? c.x[2][a] : 0.0};
          for (const std::uint32_t b : near) {
            const double xb[3] = {c.x[0][b], c.x[1][b], D == 3 ? c.x[2][b] : 0.0};
            double d[3];
            const double r = std::sqrt(separation<D, WallsY>(xa, xb, box.length, d));
            worst = std::max(worst, c.radius[a] + c.radius[b] - r);
          }
        });
  }
  if constexpr (WallsY)
    for (std::size_t a = 0; a < c.size(); ++a)
      worst = std::max({worst, c.radius[a] - c.x[1][a], c.x[1][a] + c.radius[a] - box.length[1]});
  return worst;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

} // namespace

double packing_work(std::size_t n) {
  const auto colloids = static_cast<double>(n);
  return colloids * (1e4 + colloids);
}

double max_overlap(const Colloids &c, const mpcd::Box &box) {
  if (box.dim == 2)
    return box.walls_y ? deepest<2, true>(c, box) : deepest<2, false>(c, box);
  return box.walls_y ? deepest<3, true>(c, box) : deepest<3, false>(c, box);
}

void number_along_x(Colloids &c) {
  const std::size_t n = c.size();
  std::vector<std::size_t> rows(n), by_x;
  std::iota(rows.begin(), rows.end(), std::size_t{0});
  const auto kind_before = [&](std::size_t a, std::size_t b) {
    return c.radius[a] < c.radius[b] || (c.radius[a] == c.radius[b] && c.mass[a] < c.mass[b]);
  };
  std::stable_sort(rows.begin(), rows.end(), kind_before); // (a kind's rows in row order)
  const Colloids was = c;
  const species::Table into = table(c), out_of = table(was);
  for (std::size_t g0 = 0, g1 = 0; g0 < n; g0 = g1) {
    g1 = g0 + 1;
    while (g1 < n && !kind_before(rows[g0], rows[g1]))
      ++g1;
    by_x.assign(rows.begin() + static_cast<std::ptrdiff_t>(g0),
                rows.begin() + static_cast<std::ptrdiff_t>(g1));
    std::stable_sort(by_x.begin(), by_x.end(),
                     [&](std::size_t a, std::size_t b) { return was.x[0][a] < was.x[0][b]; });
    for (std::size_t t = 0; t < by_x.size(); ++t) {
      // The state moves to the row `to` (every field: radius and mass are equal within a
      // kind); the id stays with the row.
      const std::size_t to = rows[g0 + t], from = by_x[t];
      into.copy_row(to, out_of, from);
      c.id[to] = was.id[to];
    }
  }
}

PackingReport pack_colloids(Colloids &c, const mpcd::Box &box, std::uint64_t seed,
                            const std::string &key, const PackingParams &params) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = c.size();
  const int D = box.dim;
  PackingReport report;
  if (n == 0)
    return report;
  const std::vector<double> target = c.radius;
  const double r_min = *std::min_element(target.begin(), target.end());
  double volume = 1.0, filled = 0.0;
  for (int k = 0; k < D; ++k)
    volume *= box.length[k];
  for (const double r : target)
    filled += colloid_volume(D, r);
  report.fraction = filled / volume;

  // Points at random: uniform along the periodic axes, with walls at least the own radius off
  // them (the wall springs would push them there anyway).
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = rng::draw(seed, rng::Purpose::colloid_placement, packing_draw, c.id[i]);
    const auto r2 = rng::draw(seed, rng::Purpose::colloid_placement, packing_draw + 1, c.id[i]);
    const double u[3] = {rng::uniform53(r[0], r[1]), rng::uniform53(r[2], r[3]),
                         rng::uniform53(r2[0], r2[1])};
    for (int k = 0; k < D; ++k)
      c.x[k][i] = k == 1 && box.walls_y ? target[i] + u[k] * (box.length[1] - 2.0 * target[i])
                                        : u[k] * box.length[k];
    for (int k = 0; k < 3; ++k) {
      if (k < D)
        c.v[k][i] = 0.0;
      c.omega[k][i] = 0.0;
    }
  }

  // Frictionless unit springs: the minimum's positions do not depend on k_n.
  SpringParams sp;
  sp.kn = 1.0;
  sp.kt = 0.0;
  sp.mu_cc = sp.mu_cw = 0.0;
  sp.substeps = 1;
  SpringContacts springs(sp, box);
  ContactHistory none; // read only: frictionless contacts keep no spring
  none.dim = D;
  const int S = springs.stride();
  std::vector<double> f(n * static_cast<std::size_t>(D)), v(f.size(), 0.0);
  const auto forces = [&] {
    springs.compute(c, n, none, 0.0);
    const auto &s = springs.sums();
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k)
        f[i * D + k] = fixed::to_double(s[i * S + k]);
  };

  // FIRE until the deepest overlap is below `goal` (checked every `every` iterations): true,
  // or false after params.patience iterations (stuck: jammed with overlaps).
  constexpr int every = 10;
  const auto relax = [&](double goal, double scale) {
    double dt = 0.05, alpha = 0.1;
    const double dt_max = 0.2;
    int positive = 0;
    std::fill(v.begin(), v.end(), 0.0);
    for (std::int64_t it = 0;; ++it) {
      if (it % every == 0 && params.poll)
        params.poll();
      if (it % every == 0 && max_overlap(c, box) < goal)
        return true;
      if (it >= params.patience)
        return false;
      if (report.iterations >= params.max_iterations || report.shakes > params.max_shakes)
        throw input_error(key + ": the colloids of area (volume) fraction " +
                          number(report.fraction) + " cannot be packed: after " +
                          std::to_string(report.iterations) + " relaxation steps and " +
                          std::to_string(report.shakes) + " shakes at radii scaled by " +
                          number(scale) + " the deepest overlap is " +
                          number(max_overlap(c, box) / r_min) +
                          " of the smallest radius; allowed: a deepest overlap below " +
                          number(params.tolerance) + " (a smaller packing fraction)");
      ++report.iterations;
      forces();
      double P = 0.0, vv = 0.0, ff = 0.0;
      for (std::size_t j = 0; j < f.size(); ++j) {
        P += f[j] * v[j];
        vv += v[j] * v[j];
        ff += f[j] * f[j];
      }
      if (P > 0.0) {
        const double mix = ff > 0.0 ? alpha * std::sqrt(vv / ff) : 0.0;
        for (std::size_t j = 0; j < f.size(); ++j)
          v[j] = (1.0 - alpha) * v[j] + mix * f[j];
        if (++positive > 5) {
          dt = std::min(1.1 * dt, dt_max);
          alpha *= 0.99;
        }
      } else {
        std::fill(v.begin(), v.end(), 0.0);
        dt *= 0.5;
        alpha = 0.1;
        positive = 0;
      }
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < D; ++k) {
          const std::size_t j = i * D + k;
          v[j] += dt * f[j];
          double x = c.x[k][i] + dt * v[j];
          if (k == 1 && box.walls_y)
            x = std::clamp(x, 0.0, std::nextafter(box.length[1], 0.0));
          else
            x = mpcd::wrap_periodic(x, box.length[k]);
          c.x[k][i] = x;
        }
    }
  };

  // Grow: the fraction rises by params.growth of the target per stage, by a tenth of that
  // beyond 90 % of it (where the packing approaches jamming). A stage that stays jammed with
  // overlaps is shaken: the radii go back by `back` growth steps, every centre moves by a
  // random amount up to `jolt` of its radius (draws keyed by the shake and the id), and the
  // growth starts again from there.
  double s = params.start;
  const auto fine = [&](double phi) { return phi < 0.9 ? params.growth : 0.1 * params.growth; };
  for (;;) {
    for (std::size_t i = 0; i < n; ++i)
      c.radius[i] = s * target[i];
    ++report.stages;
    const bool done = relax(params.tolerance * s * r_min, s);
    const double phi = std::pow(s, D); // relative to the target
    if (!done) {
      ++report.shakes;
      s = std::pow(std::max(phi - params.back * fine(phi), std::pow(params.start, D)), 1.0 / D);
      const auto shake = static_cast<std::uint64_t>(report.shakes);
      for (std::size_t i = 0; i < n; ++i) {
        const auto r =
            rng::draw(seed, rng::Purpose::colloid_placement, packing_draw + 2 * shake, c.id[i]);
        const auto r2 =
            rng::draw(seed, rng::Purpose::colloid_placement, packing_draw + 2 * shake + 1, c.id[i]);
        const double u[3] = {rng::uniform53(r[0], r[1]) - 0.5, rng::uniform53(r[2], r[3]) - 0.5,
                             rng::uniform53(r2[0], r2[1]) - 0.5};
        for (int k = 0; k < D; ++k) {
          double x = c.x[k][i] + 2.0 * params.jolt * s * target[i] * u[k];
          if (k == 1 && box.walls_y)
            x = std::clamp(x, 0.0, std::nextafter(box.length[1], 0.0));
          else
            x = mpcd::wrap_periodic(x, box.length[k]);
          c.x[k][i] = x;
        }
      }
      continue;
    }
    if (s >= 1.0)
      break;
    s = std::min(1.0, std::pow(phi + fine(phi), 1.0 / D));
  }
  c.radius = target;
  for (int k = 0; k < D; ++k)
    std::fill(c.v[k].begin(), c.v[k].end(), 0.0);
  number_along_x(c);
  report.max_overlap = max_overlap(c, box) / r_min;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

} // namespace narrows::colloids
