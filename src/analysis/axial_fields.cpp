// Colloid fields along the channel from the power cells (see the header).
#include "narrows/analysis/axial_fields.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace narrows::analysis {

namespace {

// Sums of phi_i A_ib and phi_i A_ib u_i over the bins along x, A_ib the part of cell i in bin b.
// Bin k (any integer; bin k mod bins inside the box) spans [k L / bins, (k + 1) L / bins): the
// same expression for an edge from either side, so neighbouring pieces share it exactly.
struct BinSums {
  double L, nb;
  std::vector<double> weight, momentum;
  BinSums(double length, std::size_t bins)
      : L(length), nb(static_cast<double>(bins)), weight(bins, 0.0), momentum(bins, 0.0) {}

  // One cell spanning [lo, hi] along x; piece(a, b) is its area (volume) between x = a and b.
  template <class Piece> void add(double lo, double hi, double phi, double u, Piece piece) {
    const auto first = static_cast<long long>(std::floor(lo / L * nb));
    const auto last = static_cast<long long>(std::floor(hi / L * nb));
    const auto m = static_cast<long long>(weight.size());
    for (long long k = first; k <= last; ++k) {
      const double part = piece(edge(k), edge(k + 1));
      if (!(part > 0.0))
        continue;
      const auto b = static_cast<std::size_t>(((k % m) + m) % m);
      weight[b] += phi * part;
      momentum[b] += phi * part * u;
    }
  }

  // phi per bin (bin_measure: a bin's area or volume) and the material-weighted velocity.
  void finish(double bin_measure, std::vector<double> &phi, std::vector<double> &velocity) const {
    const std::size_t bins = weight.size();
    phi.resize(bins);
    velocity.resize(bins);
    for (std::size_t b = 0; b < bins; ++b) {
      phi[b] = weight[b] / bin_measure;
      velocity[b] =
          weight[b] > 0.0 ? momentum[b] / weight[b] : std::numeric_limits<double>::quiet_NaN();
    }
  }

private:
  double edge(long long k) const { return static_cast<double>(k) * L / nb; }
};

} // namespace

std::size_t axial_bin_count(double length, double bin) {
  if (!(bin > 0.0) || !(length > 0.0) || bin > length * (1.0 + 1e-9))
    return 0;
  const double n = std::round(length / bin);
  if (n < 1.0 || std::abs(n * bin - length) > 1e-9 * length)
    return 0;
  return static_cast<std::size_t>(n);
}

ColloidAxialFields colloid_axial_fields(std::span<const double> x, std::span<const double> y,
                                        std::span<const double> r, std::span<const double> u,
                                        const Point2 &length, bool periodic_y, std::size_t bins) {
  const std::size_t n = x.size();
  if (u.size() != n || bins == 0)
    throw Error(ExitCode::other, "colloid_axial_fields: " + std::to_string(u.size()) +
                                     " velocities for " + std::to_string(n) + " colloids, " +
                                     std::to_string(bins) + " bins");
  ColloidAxialFields out;
  out.cells = power_cells(x, y, r, length, {true, periodic_y});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.local_fraction.assign(n, nan);
  BinSums sums(length[0], bins);
  for (std::size_t i = 0; i < n; ++i) {
    const auto &cell = out.cells.polygon[i];
    const double area = out.cells.area[i];
    if (cell.size() < 3 || !(area > 0.0))
      continue; // hidden: no cell, no share of any bin
    const double phi = std::numbers::pi * r[i] * r[i] / area;
    out.local_fraction[i] = phi;
    double lo = cell[0][0], hi = cell[0][0];
    for (const Point2 &v : cell) {
      lo = std::min(lo, v[0]);
      hi = std::max(hi, v[0]);
    }
    sums.add(lo, hi, phi, u[i],
             [&](double a, double b) { return polygon_area(clip_x_strip(cell, a, b)); });
  }
  sums.finish(length[0] / static_cast<double>(bins) * length[1], out.phi, out.velocity);
  return out;
}

ColloidAxialFields3 colloid_axial_fields_3d(std::span<const double> x, std::span<const double> y,
                                            std::span<const double> z, std::span<const double> r,
                                            std::span<const double> u, const Point3 &length,
                                            bool periodic_y, std::size_t bins) {
  const std::size_t n = x.size();
  if (u.size() != n || bins == 0)
    throw Error(ExitCode::other, "colloid_axial_fields_3d: " + std::to_string(u.size()) +
                                     " velocities for " + std::to_string(n) + " colloids, " +
                                     std::to_string(bins) + " bins");
  ColloidAxialFields3 out;
  out.cells = power_cells_3d(x, y, z, r, length, {true, periodic_y, true});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.local_fraction.assign(n, nan);
  BinSums sums(length[0], bins);
  for (std::size_t i = 0; i < n; ++i) {
    const Polyhedron &cell = out.cells.cell[i];
    const double volume = out.cells.volume[i];
    if (cell.faces.empty() || !(volume > 0.0))
      continue;
    const double phi = 4.0 / 3.0 * std::numbers::pi * r[i] * r[i] * r[i] / volume;
    out.local_fraction[i] = phi;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto &f : cell.faces)
      for (const Point3 &v : f) {
        lo = std::min(lo, v[0]);
        hi = std::max(hi, v[0]);
      }
    sums.add(lo, hi, phi, u[i],
             [&](double a, double b) { return polyhedron_volume(clip_x_slab(cell, a, b)); });
  }
  sums.finish(length[0] / static_cast<double>(bins) * length[1] * length[2], out.phi, out.velocity);
  return out;
}

} // namespace narrows::analysis
