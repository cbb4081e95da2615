// The power diagram of disks in a box (see the header). This is the only file that includes
// CGAL: its regular triangulation gives each disk's neighbours; the cells are clipped here.
#include "narrows/analysis/power_diagram.hpp"

#include "narrows/core/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

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
using VertexBase3 =
    CGAL::Triangulation_vertex_base_with_info_3<std::size_t, Kernel,
                                                CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase3 = CGAL::Regular_triangulation_cell_base_3<Kernel>;
using Tds3 = CGAL::Triangulation_data_structure_3<VertexBase3, CellBase3>;
using Regular3 = CGAL::Regular_triangulation_3<Kernel, Tds3>;

// A disk of the triangulation: an original (disk < n) or a periodic image of disk `disk`.
struct Site {
  double x, y, r;
  std::size_t disk;
};

// A ball of the 3D triangulation.
struct Site3 {
  Point3 p;
  double r;
};

double dot(const Point3 &a, const Point3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 minus(const Point3 &a, const Point3 &b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 cross(const Point3 &a, const Point3 &b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The part of a convex polyhedron where side(u) <= 0, side affine; `normal` points out of the
// kept part across the plane side = 0. An edge crossing the plane is cut from its
// lexicographically smaller end, so the two faces sharing it get the same point, bit for bit
// (`cut(p, q, sp, sq)`), and the new face is the set of those points (and of the vertices on
// the plane), in counter-clockwise order around the normal.
template <class Side, class Cut>
Polyhedron clip_polyhedron(const Polyhedron &poly, const Side &side, const Cut &cut,
                           const Point3 &normal) {
  Polyhedron out;
  std::vector<Point3> cap;
  bool face_on_plane = false;
  for (const auto &f : poly.faces) {
    std::vector<Point3> g;
    const std::size_t m = f.size();
    bool all_on = true;
    for (std::size_t j = 0; j < m; ++j) {
      const Point3 &p = f[j], &q = f[(j + 1) % m];
      const double sp = side(p), sq = side(q);
      all_on = all_on && sp == 0.0;
      if (sp <= 0.0) {
        g.push_back(p);
        if (sp == 0.0)
          cap.push_back(p);
      }
      if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
        const Point3 c = p < q ? cut(p, q, sp, sq) : cut(q, p, sq, sp);
        g.push_back(c);
        cap.push_back(c);
      }
    }
    face_on_plane = face_on_plane || (all_on && m >= 3);
    if (g.size() >= 3)
      out.faces.push_back(std::move(g));
  }
  std::sort(cap.begin(), cap.end());
  cap.erase(std::unique(cap.begin(), cap.end()), cap.end());
  if (cap.size() < 3 || face_on_plane || out.faces.empty())
    return out;
  Point3 centre{0.0, 0.0, 0.0};
  for (const Point3 &c : cap)
    for (int k = 0; k < 3; ++k)
      centre[k] += c[k] / static_cast<double>(cap.size());
  const double nn = std::sqrt(dot(normal, normal));
  const Point3 n{normal[0] / nn, normal[1] / nn, normal[2] / nn};
  const Point3 other = std::abs(n[0]) < 0.9 ? Point3{1.0, 0.0, 0.0} : Point3{0.0, 1.0, 0.0};
  Point3 e1 = cross(n, other);
  const double l1 = std::sqrt(dot(e1, e1));
  e1 = {e1[0] / l1, e1[1] / l1, e1[2] / l1};
  const Point3 e2 = cross(n, e1); // e1 x e2 = n: increasing angle is counter-clockwise about n
  std::vector<std::pair<double, Point3>> around;
  for (const Point3 &c : cap) {
    const Point3 d = minus(c, centre);
    around.emplace_back(std::atan2(dot(d, e2), dot(d, e1)), c);
  }
  std::sort(around.begin(), around.end());
  std::vector<Point3> face;
  for (const auto &a : around)
    face.push_back(a.second);
  out.faces.push_back(std::move(face));
  return out;
}

// The part of a convex polyhedron with u[axis] <= c (below) or >= c, new vertices exactly on it.
Polyhedron clip_axis(const Polyhedron &poly, int axis, double c, bool below) {
  const double s = below ? 1.0 : -1.0;
  Point3 normal{0.0, 0.0, 0.0};
  normal[axis] = s;
  return clip_polyhedron(
      poly, [&](const Point3 &u) { return s * (u[axis] - c); },
      [&](const Point3 &p, const Point3 &q, double sp, double sq) {
        const double t = sp / (sp - sq);
        Point3 r{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
        r[axis] = c;
        return r;
      },
      normal);
}

// The box [lo, hi] as a polyhedron (faces counter-clockwise seen from outside).
Polyhedron box_polyhedron(const Point3 &lo, const Point3 &hi) {
  Polyhedron b;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3; // e_i x e_j = e_k
    for (const bool upper : {false, true}) {
      std::vector<Point3> f(4);
      const double a[4][2] = {{lo[i], lo[j]}, {hi[i], lo[j]}, {hi[i], hi[j]}, {lo[i], hi[j]}};
      for (int v = 0; v < 4; ++v) {
        f[v][k] = upper ? hi[k] : lo[k];
        f[v][i] = a[v][0];
        f[v][j] = a[v][1];
      }
      if (!upper)
        std::reverse(f.begin(), f.end());
      b.faces.push_back(std::move(f));
    }
  }
  return b;
}

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

Polyhedron clip_half_space(const Polyhedron &p, const Point3 &a, double b) {
  return clip_polyhedron(
      p, [&](const Point3 &u) { return dot(a, u) - b; },
      [](const Point3 &u, const Point3 &v, double su, double sv) {
        const double t = su / (su - sv);
        return Point3{u[0] + t * (v[0] - u[0]), u[1] + t * (v[1] - u[1]), u[2] + t * (v[2] - u[2])};
      },
      a);
}

Polyhedron clip_x_slab(const Polyhedron &p, double lo, double hi) {
  return clip_axis(clip_axis(p, 0, lo, false), 0, hi, true);
}

double polyhedron_volume(const Polyhedron &p) {
  if (p.faces.empty())
    return 0.0;
  const Point3 o = p.faces[0][0];
  double six = 0.0;
  for (const auto &f : p.faces) {
    const Point3 a = minus(f[0], o);
    for (std::size_t j = 1; j + 1 < f.size(); ++j)
      six += dot(a, cross(minus(f[j], o), minus(f[j + 1], o)));
  }
  return six / 6.0;
}

PowerCells3 power_cells_3d(std::span<const double> x, std::span<const double> y,
                           std::span<const double> z, std::span<const double> r,
                           const Point3 &length, const std::array<bool, 3> &periodic) {
  const std::size_t n = x.size();
  if (y.size() != n || z.size() != n || r.size() != n)
    throw Error(ExitCode::other, "power_cells_3d: arrays of different lengths");
  PowerCells3 out;
  out.cell.resize(n);
  out.volume.assign(n, 0.0);
  if (n == 0)
    return out;
  double rmax = 0.0;
  for (const double ri : r)
    rmax = std::max(rmax, ri);
  const double spacing = std::cbrt(length[0] * length[1] * length[2] / static_cast<double>(n));
  Point3 margin{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k)
    if (periodic[k])
      margin[k] = std::min(length[k], 2.0 * (2.0 * rmax + spacing));
  std::vector<Site3> sites;
  std::vector<std::pair<Regular3::Weighted_point, std::size_t>> points;
  std::vector<Regular3::Vertex_handle> vertex, adjacent;
  std::vector<std::size_t> neighbours;
  for (;;) {
    ++out.rounds;
    sites.clear();
    for (std::size_t i = 0; i < n; ++i)
      sites.push_back({{x[i], y[i], z[i]}, r[i]});
    for (std::size_t i = 0; i < n; ++i)
      for (int ox = -1; ox <= 1; ++ox)
        for (int oy = -1; oy <= 1; ++oy)
          for (int oz = -1; oz <= 1; ++oz) {
            const int o[3] = {ox, oy, oz};
            if (ox == 0 && oy == 0 && oz == 0)
              continue;
            const Point3 p{x[i] + ox * length[0], y[i] + oy * length[1], z[i] + oz * length[2]};
            bool inside = true;
            for (int k = 0; k < 3; ++k)
              inside = inside && (o[k] == 0 || (periodic[k] && p[k] >= -margin[k] &&
                                                p[k] < length[k] + margin[k]));
            if (inside)
              sites.push_back({p, r[i]});
          }
    out.replicas = sites.size() - n;
    points.clear();
    for (std::size_t s = 0; s < sites.size(); ++s)
      points.emplace_back(
          Regular3::Weighted_point(Kernel::Point_3(sites[s].p[0], sites[s].p[1], sites[s].p[2]),
                                   sites[s].r * sites[s].r),
          s);
    Regular3 rt;
    rt.insert(points.begin(), points.end());
    vertex.assign(n, Regular3::Vertex_handle());
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
      if (v->info() < n)
        vertex[v->info()] = v;
    const bool flat = rt.dimension() < 3;
    bool proven = true;
    out.hidden = 0;
    for (std::size_t i = 0; i < n; ++i) {
      out.cell[i].faces.clear();
      out.volume[i] = 0.0;
      if (vertex[i] == Regular3::Vertex_handle()) {
        ++out.hidden;
        continue;
      }
      neighbours.clear();
      if (flat) {
        for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
          if (v->info() != i)
            neighbours.push_back(v->info());
      } else {
        adjacent.clear();
        rt.finite_adjacent_vertices(vertex[i], std::back_inserter(adjacent));
        for (const auto &v : adjacent)
          neighbours.push_back(v->info());
      }
      const Site3 &p = sites[i];
      Point3 lo, hi;
      for (int k = 0; k < 3; ++k) {
        lo[k] = periodic[k] ? -0.5 * length[k] : -p.p[k];
        hi[k] = periodic[k] ? 0.5 * length[k] : length[k] - p.p[k];
      }
      Polyhedron cell = box_polyhedron(lo, hi);
      for (const std::size_t s : neighbours) {
        const Site3 &q = sites[s];
        const Point3 d = minus(q.p, p.p);
        cell = clip_half_space(cell, {2.0 * d[0], 2.0 * d[1], 2.0 * d[2]},
                               dot(d, d) + p.r * p.r - q.r * q.r);
      }
      out.volume[i] = polyhedron_volume(cell);
      double reach = 0.0;
      for (const auto &f : cell.faces)
        for (const Point3 &u : f)
          reach = std::max(reach, std::sqrt(dot(u, u)));
      double gap = INFINITY;
      for (int k = 0; k < 3; ++k)
        if (periodic[k])
          gap = std::min(gap, std::min(p.p[k] + margin[k], length[k] + margin[k] - p.p[k]));
      if (gap < reach + std::sqrt(std::max(0.0, reach * reach - p.r * p.r + rmax * rmax)))
        proven = false;
      for (auto &f : cell.faces)
        for (Point3 &u : f)
          for (int k = 0; k < 3; ++k)
            u[k] += p.p[k];
      out.cell[i] = std::move(cell);
    }
    bool whole = true;
    for (int k = 0; k < 3; ++k)
      whole = whole && (!periodic[k] || margin[k] >= length[k]);
    if (proven || whole)
      return out;
    for (int k = 0; k < 3; ++k)
      margin[k] = std::min(length[k], 2.0 * margin[k]);
  }
}

} // namespace narrows::analysis
