// Which colloid, if any, holds a point: a grid of cells (half a unit wide in 2D, where the
// finer grid halves the fluid near a surface that needs a distance test; a unit in 3D) over this
// rank's region of x columns (its slab widened by the ghost extent; the whole box on one rank) and
// all of y and z, each cell listing the colloids whose disc or sphere reaches into it, with their
// centre and squared radius at build time (one cache line an entry). Used by the no-slip coupling
// to find the fluid particles that streamed into a colloid; the colloids must not move after
// build() while it is asked.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace narrows::coupling {

class ColloidLookup {
public:
  // Lists the rows of c (owned and ghosts) over the columns [first - extent, end + extent).
  void build(const colloids::Colloids &c, const mpcd::Box &box, int first_column, int columns,
             double extent);
  // The row of the colloid whose interior holds p (the lowest id if several), or -1. Inline:
  // every fluid particle asks once a step, and most cells list no colloid.
  long inside(const colloids::Colloids &c, const double *p) const {
    const int cell = cell_of(p);
    if (cell < 0 || head_[static_cast<std::size_t>(cell)] < 0)
      return -1;
    return inside_listed(c, p, cell);
  }

  // Of the points (x[j], y[j], z[j]) for j < m (z null in 2D), the offsets j of those whose cell
  // lists a colloid, in order, into `found`, and their cells into `found_cell` (for
  // inside_listed); returns how many. (The points elsewhere are inside none.) The cells first,
  // in a loop the compiler vectorises, then a pass without branches.
  std::size_t listed_block(const double *x, const double *y, const double *z, std::size_t m,
                           std::uint32_t *found, std::int32_t *found_cell) const;
  // inside() for a point whose cell lists a colloid (cell_of, or listed_block's found_cell).
  // Inline: asked for most fluid particles of a dense suspension every step.
  long inside_listed(const colloids::Colloids &c, const double *p, int cell) const {
    long best = -1;
    if (box_.dim == 2 && box_.walls_y) { // the channel in the plane: the same sums, unrolled
      const double Lx = box_.length[0];
      for (int e = head_[static_cast<std::size_t>(cell)]; e >= 0;) {
        const Entry &entry = entries_[static_cast<std::size_t>(e)];
        const Disc &disc = discs_[static_cast<std::size_t>(entry.row)];
        const double dx = colloids::minimum_image(p[0] - disc.x[0], Lx), dy = p[1] - disc.x[1];
        const double r2 = std::fma(dy, dy, dx * dx); // (fused as the loop below is)
        if (r2 < disc.r2 && (best < 0 || c.id[entry.row] < c.id[best]))
          best = entry.row;
        e = entry.next;
      }
      return best;
    }
    for (int e = head_[static_cast<std::size_t>(cell)]; e >= 0;) {
      const Entry &entry = entries_[static_cast<std::size_t>(e)];
      const Disc &disc = discs_[static_cast<std::size_t>(entry.row)];
      double r2 = 0.0;
      for (int k = 0; k < box_.dim; ++k) {
        double d = p[k] - disc.x[k];
        if (!(k == 1 && box_.walls_y))
          d = colloids::minimum_image(d, box_.length[k]);
        r2 += d * d;
      }
      if (r2 < disc.r2 && (best < 0 || c.id[entry.row] < c.id[best]))
        best = entry.row;
      e = entry.next;
    }
    return best;
  }
  static constexpr std::size_t block = 512; // the largest m

  // Whether the cell of p lists a colloid (a point elsewhere is inside none); branch-free, for
  // a first pass over many points.
  bool listed(const double *p) const {
    const int cell = cell_of(p);
    return (cell >= 0) & (listed_[static_cast<std::size_t>(cell < 0 ? 0 : cell)] != 0);
  }

private:
  // The cell of p, -1 outside the region. Positions lie in [0, L) along periodic axes and in
  // [0, L_y] between walls (streamed and wrapped): truncation is the floor, and one addition
  // wraps the column into the region.
  int cell_of(const double *p) const {
    int ix = std::min(static_cast<int>(p[0] * per_unit_), lx_ - 1) - lo_;
    ix += ix < 0 ? lx_ : 0;
    if (ix >= nx_)
      return -1;
    const int iy = std::clamp(static_cast<int>(p[1] * per_unit_), 0, ny_ - 1); // y = L_y: wall
    const int iz = box_.dim == 3 ? std::clamp(static_cast<int>(p[2] * per_unit_), 0, nz_ - 1) : 0;
    return ix + nx_ * (iy + ny_ * iz);
  }
  struct Entry {
    int row;  // the colloid's row in c
    int next; // the cell's next entry, -1 at the end
  };
  struct Disc {
    double x[3], r2; // a colloid's centre and squared radius at build time
  };
  mpcd::Box box_;
  double per_unit_ = 1.0;                 // lookup cells per unit length
  int lx_ = 1;                            // lookup columns of the whole box
  int lo_ = 0, nx_ = 1, ny_ = 1, nz_ = 1; // region: columns lo_ .. lo_ + nx_ - 1 (wrapped)
  std::vector<int> head_;
  std::vector<std::uint8_t> listed_; // head_ >= 0, a quarter of the bytes for the first pass
  std::vector<Entry> entries_;
  std::vector<Disc> discs_;         // per row of c
  std::vector<double> column_gap2_; // build(): per column of one colloid, its squared x gap
  std::vector<int> column_index_;   // and its column in the region (-1: outside)
};

} // namespace narrows::coupling
