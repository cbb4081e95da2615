// The power (Voronoi) cells of the colloids and the fields along the channel built on them
// (analysis/power_diagram.hpp, analysis/axial_fields.hpp; Kanehl (thesis) eq 6.1):
// - a hexagonal packing of equal disks, periodic both ways, has the analytic fraction
//   pi a^2 / ((sqrt 3 / 2) d^2) in every cell and every bin;
// - random polydisperse disks between walls: the cells tile the channel (areas sum to its
//   area), every random point of the channel lies in the cell of the disk of least power
//   (brute force over all disks and their periodic images), the channel mean of phi(x) is the
//   colloid area over the channel area and the material-weighted mean of v(x) the mean colloid
//   momentum;
// - a sparse channel (the replication margin must grow), one disk alone, disks on one line (a
//   flat triangulation), a hidden disk;
// - 3D: a bcc packing (truncated octahedra of volume a^3/2), random polydisperse balls in a slit
//   (volumes tile it, points in the cell of least power, channel means), one ball alone.
// Tolerances: the areas are sums of ~10 products of coordinates of size <= 100, each rounded to
// 1e-16 relative, so 1e-12 relative leaves a factor ~100 for the sums of hundreds of cells.
#include "narrows/analysis/axial_fields.hpp"
#include "narrows/analysis/power_diagram.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace narrows::analysis;

namespace {

struct Disks {
  std::vector<double> x, y, r, u;
};

// Random disks of radii in [rmin, rmax] without overlap, within the channel [0, lx) x [0, ly)
// (walls: centres at least a radius from them; periodic along x).
Disks random_disks(std::size_t n, double lx, double ly, double rmin, double rmax, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Disks d;
  while (d.x.size() < n) {
    const double r = rmin + (rmax - rmin) * unit(gen);
    const double x = lx * unit(gen), y = r + (ly - 2 * r) * unit(gen);
    bool free = true;
    for (std::size_t j = 0; j < d.x.size() && free; ++j) {
      double dx = std::abs(x - d.x[j]);
      dx = std::min(dx, lx - dx);
      const double dy = y - d.y[j];
      free = dx * dx + dy * dy >= (r + d.r[j]) * (r + d.r[j]);
    }
    if (free) {
      d.x.push_back(x);
      d.y.push_back(y);
      d.r.push_back(r);
      d.u.push_back(unit(gen) - 0.3);
    }
  }
  return d;
}

bool inside(const std::vector<Point2> &polygon, double px, double py) {
  // Convex, counter-clockwise: on the left of (or on) every edge.
  const std::size_t m = polygon.size();
  for (std::size_t j = 0; j < m; ++j) {
    const Point2 &a = polygon[j], &b = polygon[(j + 1) % m];
    if ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]) < -1e-9)
      return false;
  }
  return m >= 3;
}

// Points of the channel that lie in the cell of a disk other than the one of least power
// (brute force over every disk and its images one length away along each periodic axis).
int points_in_wrong_cells(const Disks &d, const PowerCells &cells, double lx, double ly,
                          bool periodic_y, int points, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int wrong = 0;
  for (int s = 0; s < points; ++s) {
    const double px = lx * unit(gen), py = ly * unit(gen);
    std::size_t best = 0;
    double least = INFINITY, second = INFINITY;
    for (std::size_t i = 0; i < d.x.size(); ++i)
      for (int ox = -1; ox <= 1; ++ox)
        for (int oy = periodic_y ? -1 : 0; oy <= (periodic_y ? 1 : 0); ++oy) {
          const double dx = px - d.x[i] - ox * lx, dy = py - d.y[i] - oy * ly;
          const double power = dx * dx + dy * dy - d.r[i] * d.r[i];
          if (power < least) {
            if (i != best)
              second = least;
            least = power;
            best = i;
          } else if (i != best && power < second) {
            second = power;
          }
        }
    if (second - least < 1e-9)
      continue; // on a cell edge
    // The cell of `best` holds the point or one of its images.
    bool found = false;
    for (int ox = -1; ox <= 1 && !found; ++ox)
      for (int oy = periodic_y ? -1 : 0; oy <= (periodic_y ? 1 : 0) && !found; ++oy)
        found = inside(cells.polygon[best], px + ox * lx, py + oy * ly);
    wrong += !found;
  }
  return wrong;
}

double total(const std::vector<double> &v) {
  double s = 0.0;
  for (const double a : v)
    s += a;
  return s;
}

} // namespace

TEST(PowerDiagram, HexagonalPackingHasTheAnalyticFractionPerCellAndBin) {
  // 12 x 8 disks of radius a on a triangular lattice of spacing d, shifted off the box edges;
  // rows sqrt(3)/2 d apart, every other row shifted by d/2 (8 rows: periodic along y).
  const double d = 2.5, a = 1.1, h = std::sqrt(3.0) / 2.0 * d;
  const int columns = 12, rows = 8;
  const double lx = columns * d, ly = rows * h;
  Disks disks;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      disks.x.push_back(std::fmod(0.37 + i * d + (j % 2) * 0.5 * d, lx));
      disks.y.push_back(0.21 + j * h);
      disks.r.push_back(a);
      disks.u.push_back(0.5);
    }
  const double want = std::numbers::pi * a * a / (h * d);
  // Bins that cut cells anywhere: 7 bins of lx/7 (no multiple of d/2).
  const auto f = colloid_axial_fields(disks.x, disks.y, disks.r, disks.u, {lx, ly}, true, 7);
  EXPECT_EQ(f.cells.hidden, 0u);
  for (std::size_t i = 0; i < disks.x.size(); ++i) {
    EXPECT_NEAR(f.cells.area[i], h * d, 1e-12 * h * d) << "cell " << i;
    EXPECT_NEAR(f.local_fraction[i], want, 1e-12 * want) << "cell " << i;
    EXPECT_EQ(f.cells.polygon[i].size(), 6u) << "cell " << i << " is no hexagon";
  }
  for (std::size_t b = 0; b < f.phi.size(); ++b) {
    EXPECT_NEAR(f.phi[b], want, 1e-12 * want) << "bin " << b;
    EXPECT_NEAR(f.velocity[b], 0.5, 1e-12) << "bin " << b;
  }
}

TEST(PowerDiagram, PolydisperseCellsTileTheChannelAndHoldTheirPoints) {
  const double lx = 60.0, ly = 15.0;
  const Disks d = random_disks(260, lx, ly, 0.5, 1.5, 11);
  const std::size_t bins = 30;
  const auto f = colloid_axial_fields(d.x, d.y, d.r, d.u, {lx, ly}, false, bins);
  EXPECT_EQ(f.cells.hidden, 0u);
  EXPECT_NEAR(total(f.cells.area), lx * ly, 1e-12 * lx * ly);
  for (std::size_t i = 0; i < d.x.size(); ++i) {
    EXPECT_GT(f.cells.area[i], std::numbers::pi * d.r[i] * d.r[i]) << "cell " << i;
    for (const Point2 &v : f.cells.polygon[i]) { // between the walls
      EXPECT_GE(v[1], 0.0);
      EXPECT_LE(v[1], ly);
    }
  }
  EXPECT_EQ(points_in_wrong_cells(d, f.cells, lx, ly, false, 20000, 5), 0);
  // Channel means: sum_b phi_b A_b = sum_i V_i and sum_b phi_b v_b A_b = sum_i V_i u_i.
  double volume = 0.0, momentum = 0.0, phi_area = 0.0, phi_v_area = 0.0;
  for (std::size_t i = 0; i < d.x.size(); ++i) {
    volume += std::numbers::pi * d.r[i] * d.r[i];
    momentum += std::numbers::pi * d.r[i] * d.r[i] * d.u[i];
  }
  const double bin_area = lx / bins * ly;
  for (std::size_t b = 0; b < bins; ++b) {
    phi_area += f.phi[b] * bin_area;
    phi_v_area += f.phi[b] * f.velocity[b] * bin_area;
  }
  EXPECT_NEAR(phi_area, volume, 1e-12 * volume);
  EXPECT_NEAR(phi_v_area, momentum, 1e-12 * volume);
  // Periodic along y too (no walls): the same tiling.
  const auto g = colloid_axial_fields(d.x, d.y, d.r, d.u, {lx, ly}, true, bins);
  EXPECT_NEAR(total(g.cells.area), lx * ly, 1e-12 * lx * ly);
  EXPECT_EQ(points_in_wrong_cells(d, g.cells, lx, ly, true, 20000, 6), 0);
}

TEST(PowerDiagram, SparseChannelGrowsTheMarginUntilTheCellsAreExact) {
  // Three disks in the middle of a channel 100 long: the first margin (twice a diameter plus
  // the spacing, ~34) holds no image of them, so the outer cells would overlap across x = 0;
  // it grows until they are proven, and the cells are those of brute force.
  const double lx = 100.0, ly = 6.0;
  const Disks d{{45.0, 50.0, 55.0}, {2.0, 3.5, 4.0}, {1.0, 0.6, 1.4}, {0.1, 0.2, 0.3}};
  const auto f = colloid_axial_fields(d.x, d.y, d.r, d.u, {lx, ly}, false, 25);
  EXPECT_GT(f.cells.rounds, 1);
  EXPECT_NEAR(total(f.cells.area), lx * ly, 1e-12 * lx * ly);
  EXPECT_EQ(points_in_wrong_cells(d, f.cells, lx, ly, false, 20000, 7), 0);
}

TEST(PowerDiagram, OneDiskAloneOwnsTheChannel) {
  const double lx = 30.0, ly = 8.0;
  const Disks d{{12.0}, {5.0}, {2.0}, {0.7}};
  const auto f = colloid_axial_fields(d.x, d.y, d.r, d.u, {lx, ly}, false, 6);
  EXPECT_NEAR(f.cells.area[0], lx * ly, 1e-12 * lx * ly);
  const double want = std::numbers::pi * 4.0 / (lx * ly);
  for (std::size_t b = 0; b < 6; ++b) {
    EXPECT_NEAR(f.phi[b], want, 1e-12 * want) << "bin " << b;
    EXPECT_NEAR(f.velocity[b], 0.7, 1e-12) << "bin " << b;
  }
}

TEST(PowerDiagram, DisksOnOneLineAndAHiddenDisk) {
  // A chain along x (with its images: all on one line, a flat triangulation).
  const double lx = 40.0, ly = 10.0;
  const Disks chain{
      {1.0, 9.0, 14.0, 30.0}, {5.0, 5.0, 5.0, 5.0}, {1.0, 2.0, 1.0, 1.5}, {0.0, 0.0, 0.0, 0.0}};
  const auto f = colloid_axial_fields(chain.x, chain.y, chain.r, chain.u, {lx, ly}, false, 8);
  EXPECT_NEAR(total(f.cells.area), lx * ly, 1e-12 * lx * ly);
  EXPECT_EQ(points_in_wrong_cells(chain, f.cells, lx, ly, false, 5000, 8), 0);
  // A small disk at the centre of a large one has no cell (power diagrams hide it: its power
  // exceeds the large one's everywhere); the others still tile the channel, its fraction is NaN.
  const Disks hid{{10.0, 10.0, 25.0}, {5.0, 5.0, 4.0}, {4.0, 0.5, 2.0}, {0.0, 0.0, 0.0}};
  const auto g = colloid_axial_fields(hid.x, hid.y, hid.r, hid.u, {lx, ly}, false, 8);
  EXPECT_EQ(g.cells.hidden, 1u);
  EXPECT_EQ(g.cells.area[1], 0.0);
  EXPECT_TRUE(std::isnan(g.local_fraction[1]));
  EXPECT_NEAR(total(g.cells.area), lx * ly, 1e-12 * lx * ly);
}

TEST(PowerDiagram, AxialBinCount) {
  EXPECT_EQ(axial_bin_count(600.0, 2.0), 300u);
  EXPECT_EQ(axial_bin_count(600.0, 600.0), 1u);
  EXPECT_EQ(axial_bin_count(10.0, 0.1), 100u); // 0.1 is not exact in binary
  EXPECT_EQ(axial_bin_count(25.0, 2.0), 0u);   // not a whole number of bins
  EXPECT_EQ(axial_bin_count(25.0, 30.0), 0u);  // longer than the channel
  EXPECT_EQ(axial_bin_count(25.0, 0.0), 0u);
}

namespace {

// A point in a convex polyhedron (faces counter-clockwise seen from outside).
bool inside3(const Polyhedron &p, const Point3 &u) {
  for (const auto &f : p.faces) {
    const Point3 &a = f[0], &b = f[1], &c = f[2];
    const Point3 ab{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
        ac{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Point3 n{ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2],
                   ab[0] * ac[1] - ab[1] * ac[0]};
    if (n[0] * (u[0] - a[0]) + n[1] * (u[1] - a[1]) + n[2] * (u[2] - a[2]) > 1e-9)
      return false;
  }
  return !p.faces.empty();
}

} // namespace

TEST(PowerDiagram3D, BodyCentredCubicPackingHasTheAnalyticFraction) {
  // A bcc lattice of cube side a (cells: truncated octahedra of volume a^3 / 2), 4 x 4 x 4
  // cubes, shifted off the box edges, periodic along x, y and z; 5 bins of 16/5.
  const double a = 4.0, r = 1.5;
  const int m = 4;
  const double l = m * a;
  std::vector<double> x, y, z, rr, u;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (const double h : {0.0, 0.5}) {
          x.push_back(0.31 + (i + h) * a);
          y.push_back(0.17 + (j + h) * a);
          z.push_back(0.23 + (k + h) * a);
          rr.push_back(r);
          u.push_back(-0.25);
        }
  const double want = 4.0 / 3.0 * std::numbers::pi * r * r * r / (a * a * a / 2.0);
  const auto f = colloid_axial_fields_3d(x, y, z, rr, u, {l, l, l}, true, 5);
  EXPECT_EQ(f.cells.hidden, 0u);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(f.cells.volume[i], a * a * a / 2.0, 1e-12 * a * a * a) << "cell " << i;
    EXPECT_NEAR(f.local_fraction[i], want, 1e-12 * want) << "cell " << i;
    EXPECT_EQ(f.cells.cell[i].faces.size(), 14u) << "cell " << i << " is no truncated octahedron";
  }
  for (std::size_t b = 0; b < 5; ++b) {
    EXPECT_NEAR(f.phi[b], want, 1e-12 * want) << "bin " << b;
    EXPECT_NEAR(f.velocity[b], -0.25, 1e-12) << "bin " << b;
  }
}

TEST(PowerDiagram3D, PolydisperseCellsTileTheSlitAndHoldTheirPoints) {
  // Random balls between walls at y = 0 and 8, periodic along x (20) and z (6).
  const double lx = 20.0, ly = 8.0, lz = 6.0;
  std::mt19937_64 gen(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> x, y, z, r, u;
  while (x.size() < 60) {
    const double ri = 0.5 + unit(gen), xi = lx * unit(gen), yi = ri + (ly - 2 * ri) * unit(gen),
                 zi = lz * unit(gen);
    bool free = true;
    for (std::size_t j = 0; j < x.size() && free; ++j) {
      double dx = std::abs(xi - x[j]), dz = std::abs(zi - z[j]);
      dx = std::min(dx, lx - dx);
      dz = std::min(dz, lz - dz);
      free = dx * dx + (yi - y[j]) * (yi - y[j]) + dz * dz >= (ri + r[j]) * (ri + r[j]);
    }
    if (free) {
      x.push_back(xi), y.push_back(yi), z.push_back(zi), r.push_back(ri);
      u.push_back(unit(gen) - 0.4);
    }
  }
  const std::size_t bins = 8;
  const auto f = colloid_axial_fields_3d(x, y, z, r, u, {lx, ly, lz}, false, bins);
  EXPECT_EQ(f.cells.hidden, 0u);
  EXPECT_NEAR(total(f.cells.volume), lx * ly * lz, 1e-12 * lx * ly * lz);
  double volume = 0.0, momentum = 0.0, phi_v = 0.0, phi_vu = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double vi = 4.0 / 3.0 * std::numbers::pi * r[i] * r[i] * r[i];
    volume += vi;
    momentum += vi * u[i];
  }
  const double bin_volume = lx / bins * ly * lz;
  for (std::size_t b = 0; b < bins; ++b) {
    phi_v += f.phi[b] * bin_volume;
    phi_vu += f.phi[b] * f.velocity[b] * bin_volume;
  }
  EXPECT_NEAR(phi_v, volume, 1e-12 * volume);
  EXPECT_NEAR(phi_vu, momentum, 1e-12 * volume);
  // Random points lie in the cell (or an image of it) of the ball of least power.
  int wrong = 0;
  for (int s = 0; s < 5000; ++s) {
    const Point3 p{lx * unit(gen), ly * unit(gen), lz * unit(gen)};
    std::size_t best = 0;
    double least = INFINITY, second = INFINITY;
    for (std::size_t i = 0; i < x.size(); ++i)
      for (int ox = -1; ox <= 1; ++ox)
        for (int oz = -1; oz <= 1; ++oz) {
          const double dx = p[0] - x[i] - ox * lx, dy = p[1] - y[i], dz = p[2] - z[i] - oz * lz;
          const double power = dx * dx + dy * dy + dz * dz - r[i] * r[i];
          if (power < least) {
            if (i != best)
              second = least;
            least = power;
            best = i;
          } else if (i != best && power < second) {
            second = power;
          }
        }
    if (second - least < 1e-9)
      continue;
    bool found = false;
    for (int ox = -1; ox <= 1 && !found; ++ox)
      for (int oz = -1; oz <= 1 && !found; ++oz)
        found = inside3(f.cells.cell[best], {p[0] + ox * lx, p[1], p[2] + oz * lz});
    wrong += !found;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(PowerDiagram3D, OneBallAloneOwnsTheSlit) {
  const std::vector<double> x{3.0}, y{2.0}, z{1.0}, r{1.0}, u{0.4};
  const auto f = colloid_axial_fields_3d(x, y, z, r, u, {12.0, 5.0, 4.0}, false, 3);
  EXPECT_NEAR(f.cells.volume[0], 240.0, 1e-12 * 240.0);
  for (std::size_t b = 0; b < 3; ++b)
    EXPECT_NEAR(f.phi[b], 4.0 / 3.0 * std::numbers::pi / 240.0, 1e-15) << "bin " << b;
}
