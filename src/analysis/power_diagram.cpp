// The power diagram of disks in a box (see the header). This is the only file that includes
// CGAL: its regular triangulation gives each disk's neighbours; the cells are clipped here.
#include "narrows/analysis/power_diagram.hpp"

#include "narrows/core/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace narrows::analysis {

namespace {

// Exact predicates (the combinatorics are right whatever the rounding), inexact constructions
// (none are used: the cells are built from the centres and radii below).
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase =
    CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel,
                                                CGAL::Regular_triangulation_vertex_base_2<Kernel>>;
using FaceBase = CGAL::Regular_triangulation_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Regular = CGAL::Regular_triangulation_2<Kernel, Tds>;

// A disk of the triangulation: an original (disk < n) or a periodic image of disk `disk`.
struct Site {
  double x, y, r;
  std::size_t disk;
};

} // namespace

std::vector<Point2> clip_half_plane(const std::vector<Point2> &polygon, const Point2 &a, double b) {
  std::vector<Point2> out;
  const std::size_t m = polygon.size();
  out.reserve(m + 1);
  for (std::size_t j = 0; j < m; ++j) {
    const Point2 &p = polygon[j], &q = polygon[(j + 1) % m];
    const double sp = a[0] * p[0] + a[1] * p[1] - b, sq = a[0] * q[0] + a[1] * q[1] - b;
    if (sp <= 0.0)
      out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
      const double t = sp / (sp - sq);
      out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
    }
  }
  return out;
}

namespace {

// The part of a convex polygon with x <= c (below) or x >= c; the new vertices lie exactly on
// x = c, so the pieces of two neighbouring strips share their edge bit for bit.
std::vector<Point2> clip_x(const std::vector<Point2> &polygon, double c, bool below) {
  std::vector<Point2> out;
  const std::size_t m = polygon.size();
  out.reserve(m + 1);
  const double s = below ? 1.0 : -1.0;
  for (std::size_t j = 0; j < m; ++j) {
    const Point2 &p = polygon[j], &q = polygon[(j + 1) % m];
    const double sp = s * (p[0] - c), sq = s * (q[0] - c);
    if (sp <= 0.0)
      out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
      const double t = sp / (sp - sq);
      out.push_back({c, p[1] + t * (q[1] - p[1])});
    }
  }
  return out;
}

} // namespace

std::vector<Point2> clip_x_strip(const std::vector<Point2> &polygon, double lo, double hi) {
  return clip_x(clip_x(polygon, lo, false), hi, true);
}

double polygon_area(const std::vector<Point2> &polygon) {
  double twice = 0.0;
  const std::size_t m = polygon.size();
  if (m < 3)
    return 0.0;
  const Point2 &o = polygon[0];
  for (std::size_t j = 1; j + 1 < m; ++j) {
    const double ax = polygon[j][0] - o[0], ay = polygon[j][1] - o[1];
    const double bx = polygon[j + 1][0] - o[0], by = polygon[j + 1][1] - o[1];
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

PowerCells power_cells(std::span<const double> x, std::span<const double> y,
                       std::span<const double> r, const Point2 &length,
                       const std::array<bool, 2> &periodic) {
  const std::size_t n = x.size();
  if (y.size() != n || r.size() != n)
    throw Error(ExitCode::other, "power_cells: " + std::to_string(n) + " x, " +
                                     std::to_string(y.size()) + " y and " +
                                     std::to_string(r.size()) + " radii");
  PowerCells out;
  out.polygon.resize(n);
  out.area.assign(n, 0.0);
  if (n == 0)
    return out;
  double rmax = 0.0;
  for (const double ri : r)
    rmax = std::max(rmax, ri);
  // The first margin: twice a diameter plus the mean spacing, which holds the neighbours of the
  // cells near the box's ends in a dense packing (a sparse one doubles it as needed).
  const double spacing = std::sqrt(length[0] * length[1] / static_cast<double>(n));
  std::array<double, 2> margin{0.0, 0.0};
  for (int k = 0; k < 2; ++k)
    if (periodic[k])
      margin[k] = std::min(length[k], 2.0 * (2.0 * rmax + spacing));

  std::vector<Site> sites;
  std::vector<std::pair<Regular::Weighted_point, std::size_t>> points;
  std::vector<Regular::Vertex_handle> vertex;
  std::vector<std::size_t> neighbours;
  for (;;) {
    ++out.rounds;
    // The disks, then their images within the margin (none along a wall axis).
    sites.clear();
    for (std::size_t i = 0; i < n; ++i)
      sites.push_back({x[i], y[i], r[i], i});
    for (std::size_t i = 0; i < n; ++i)
      for (int ox = periodic[0] ? -1 : 0; ox <= (periodic[0] ? 1 : 0); ++ox)
        for (int oy = periodic[1] ? -1 : 0; oy <= (periodic[1] ? 1 : 0); ++oy) {
          if (ox == 0 && oy == 0)
            continue;
          const double ix = x[i] + ox * length[0], iy = y[i] + oy * length[1];
          const bool inside = (ox == 0 || (ix >= -margin[0] && ix < length[0] + margin[0])) &&
                              (oy == 0 || (iy >= -margin[1] && iy < length[1] + margin[1]));
          if (inside)
            sites.push_back({ix, iy, r[i], i});
        }
    out.replicas = sites.size() - n;
    // The weight of a disk in the power distance |x - p|^2 - w is its radius squared.
    points.clear();
    for (std::size_t s = 0; s < sites.size(); ++s)
      points.emplace_back(
          Regular::Weighted_point(Kernel::Point_2(sites[s].x, sites[s].y), sites[s].r * sites[s].r),
          s);
    Regular rt;
    rt.insert(points.begin(), points.end());
    vertex.assign(n, Regular::Vertex_handle());
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
      if (v->info() < n)
        vertex[v->info()] = v;
    // Fewer than three disks off one line: every disk is every other's neighbour.
    const bool flat = rt.dimension() < 2;

    bool proven = true;
    out.hidden = 0;
    for (std::size_t i = 0; i < n; ++i) {
      out.polygon[i].clear();
      out.area[i] = 0.0;
      if (vertex[i] == Regular::Vertex_handle()) {
        ++out.hidden;
        continue;
      }
      neighbours.clear();
      if (flat) {
        for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
          if (v->info() != i)
            neighbours.push_back(v->info());
      } else {
        auto c = rt.incident_vertices(vertex[i]), done = c;
        do {
          if (!rt.is_infinite(c))
            neighbours.push_back(c->info());
        } while (++c != done);
      }
      // Relative to the centre p: along a periodic axis the cell lies within half a length of
      // p (the bisector with p's own image), along a wall axis within the channel.
      const Site &p = sites[i];
      const double pk[2] = {p.x, p.y};
      std::vector<Point2> cell;
      double lo[2], hi[2];
      for (int k = 0; k < 2; ++k) {
        lo[k] = periodic[k] ? -0.5 * length[k] : -pk[k];
        hi[k] = periodic[k] ? 0.5 * length[k] : length[k] - pk[k];
      }
      cell = {{lo[0], lo[1]}, {hi[0], lo[1]}, {hi[0], hi[1]}, {lo[0], hi[1]}};
      // Power half-plane of neighbour q: |u|^2 - r_p^2 <= |u - d|^2 - r_q^2 with d = q - p,
      // i.e. 2 d . u <= |d|^2 + r_p^2 - r_q^2.
      for (const std::size_t s : neighbours) {
        const Site &q = sites[s];
        const double dx = q.x - p.x, dy = q.y - p.y;
        cell =
            clip_half_plane(cell, {2.0 * dx, 2.0 * dy}, dx * dx + dy * dy + p.r * p.r - q.r * q.r);
      }
      out.area[i] = polygon_area(cell);
      double reach = 0.0; // R: the farthest point of the cell from p
      for (const Point2 &u : cell)
        reach = std::max(reach, std::hypot(u[0], u[1]));
      // A disk q left out (an image beyond the margin) could cut this cell only if some u in it
      // had |u - d|^2 - r_q^2 < |u|^2 - r_p^2 <= R^2 - r_p^2; as |u - d| >= |d| - R, no q
      // farther than R + sqrt(R^2 - r_p^2 + r_max^2) can. The images left out lie beyond the
      // margin along some periodic axis k: at least min(p_k + M_k, L_k + M_k - p_k) away.
      double gap = INFINITY;
      for (int k = 0; k < 2; ++k)
        if (periodic[k])
          gap = std::min(gap, std::min(pk[k] + margin[k], length[k] + margin[k] - pk[k]));
      if (gap < reach + std::sqrt(std::max(0.0, reach * reach - p.r * p.r + rmax * rmax)))
        proven = false;
      for (Point2 &u : cell) {
        u[0] += p.x;
        u[1] += p.y;
      }
      out.polygon[i] = std::move(cell);
    }
    // With the images of a whole length on each side the cells are exact: the cell of p lies
    // within half a length of p along each periodic axis, and there an image two lengths away
    // is never nearer (in power) than the same disk's image one length away.
    bool whole = true;
    for (int k = 0; k < 2; ++k)
      whole = whole && (!periodic[k] || margin[k] >= length[k]);
    if (proven || whole)
      return out;
    for (int k = 0; k < 2; ++k)
      margin[k] = std::min(length[k], 2.0 * margin[k]);
  }
}

} // namespace narrows::analysis
