// The power (Laguerre) diagram of disks in a 2D box: the Voronoi tessellation of the centres
// weighted by the radii (Aurenhammer (1987)), the local area fraction of a packing (Kanehl
// (thesis) eq 6.1: "a Voronoi tessellation for the colloidal packing"). The cell of disk i
// is the set of points x whose power |x - p_i|^2 - r_i^2 is smallest over all disks; with equal
// radii it is the ordinary Voronoi cell. The diagram comes from CGAL's regular triangulation
// (Yvinec (2022), Regular_triangulation_2: its neighbours are those of the power diagram), and
// each cell is the box (or channel) clipped by the power half-planes of its neighbours, so a
// cell is a convex polygon and the cells tile the box. In 3D the same with balls,
// Regular_triangulation_3 and convex polyhedra.
//
// Along a periodic axis the disks are replicated within a margin of the box; the margin starts at
// a few spacings and doubles until every cell is provably unaffected by the disks left out (see
// power_diagram.cpp), at most to one box length, where the diagram is exact. Along an axis that
// is not periodic (walls) the cells are clipped to [0, length).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace narrows::analysis {

using Point2 = std::array<double, 2>;

struct PowerCells {
  // The cell of disk i as a convex polygon (counter-clockwise vertices, absolute coordinates):
  // along a periodic axis it lies within half a box length of the centre, so it may stick out
  // of [0, length) by that much (the part outside belongs to the periodic image inside).
  std::vector<std::vector<Point2>> polygon;
  std::vector<double> area; // of each polygon; 0 for a hidden disk
  // Disks with an empty power cell (possible only for a centre inside a larger disk, with
  // |p_i - p_j|^2 < r_j^2 - r_i^2: never in a packing of disks that do not overlap).
  std::size_t hidden = 0;
  std::size_t replicas = 0; // periodic images used in the last (accepted) triangulation
  int rounds = 0;           // triangulations built (the margin doubled rounds - 1 times)
};

// The power cells of n disks (centres x, y within the box, radii r >= 0) in the box
// [0, length[0]) x [0, length[1]), periodic along axis k if periodic[k], else bounded by walls at
// 0 and length[k]. Deterministic: the same input gives the same bits.
PowerCells power_cells(std::span<const double> x, std::span<const double> y,
                       std::span<const double> r, const Point2 &length,
                       const std::array<bool, 2> &periodic);

// ---- 3D: power cells of balls as convex polyhedra ----

using Point3 = std::array<double, 3>;
// A convex polyhedron as its faces, each a convex polygon counter-clockwise seen from outside.
struct Polyhedron {
  std::vector<std::vector<Point3>> faces;
};

struct PowerCells3 {
  std::vector<Polyhedron> cell; // of ball i, absolute coordinates (as polygon in 2D)
  std::vector<double> volume;   // 0 for a hidden ball
  std::size_t hidden = 0, replicas = 0;
  int rounds = 0;
};

// The power cells of n balls in the box [0, length[k]) (periodic along k if periodic[k], else
// walls at 0 and length[k]), as power_cells in 2D (Regular_triangulation_3).
PowerCells3 power_cells_3d(std::span<const double> x, std::span<const double> y,
                           std::span<const double> z, std::span<const double> r,
                           const Point3 &length, const std::array<bool, 3> &periodic);

// The part of a convex polyhedron where a . u <= b, closed by a new face on the plane.
Polyhedron clip_half_space(const Polyhedron &p, const Point3 &a, double b);
// The part with lo <= x <= hi (new vertices exactly on the planes).
Polyhedron clip_x_slab(const Polyhedron &p, double lo, double hi);
double polyhedron_volume(const Polyhedron &p);

// ---- convex polygons (used by the cells and the bins along x) ----

// The part of a convex polygon where a . u <= b (u = vertex), in order.
std::vector<Point2> clip_half_plane(const std::vector<Point2> &polygon, const Point2 &a, double b);
// The part of a convex polygon with lo <= x < hi (an x strip).
std::vector<Point2> clip_x_strip(const std::vector<Point2> &polygon, double lo, double hi);
// Area of a polygon (shoelace, positive for counter-clockwise vertices), relative to its first
// vertex (so that far from the origin it loses no digits).
double polygon_area(const std::vector<Point2> &polygon);

} // namespace narrows::analysis
