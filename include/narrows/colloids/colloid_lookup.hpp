// Which colloid, if any, holds a point: a grid of unit cells over this rank's region of x
// columns (its slab widened by the ghost extent; the whole box on one rank) and all of y and z,
// each cell listing the colloids whose bounding box touches it. Used by the no-slip coupling
// to find the fluid particles that streamed into a colloid.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/mpcd/fluid.hpp"

#include <vector>

namespace narrows::colloids {

class ColloidLookup {
public:
  // Lists the rows of c (owned and ghosts) over the columns [first - extent, end + extent).
  void build(const Colloids &c, const mpcd::Box &box, int first_column, int columns, double extent);
  // The row of the colloid whose interior holds p (the lowest id if several), or -1.
  long inside(const Colloids &c, const double *p) const;

private:
  int cell_of(const double *p) const; // -1 outside the region
  mpcd::Box box_;
  int lo_ = 0, nx_ = 1, ny_ = 1, nz_ = 1; // region: columns lo_ .. lo_ + nx_ - 1 (wrapped)
  std::vector<int> head_, next_, row_;
};

} // namespace narrows::colloids
