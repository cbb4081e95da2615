// The fluid's exclusion test at the start of a run.
#include "narrows/colloids/placement.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace narrows::colloids {

double colloid_volume(int dim, double r) {
  return dim == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

bool inside_any(const Colloids &c, const mpcd::Box &box, const std::array<double, 3> &p) {
  for (std::size_t i = 0; i < c.size(); ++i)
    if (distance2(box, p, position(c, i)) < c.radius[i] * c.radius[i])
      return true;
  return false;
}

ColloidCover::ColloidCover(const Colloids &c, const mpcd::Box &box) : c_(c), box_(box) {
  // Each colloid covers the cells of its bounding box (wrapped along periodic axes, clipped
  // along the wall axis); two passes build the lists, counts first.
  const std::size_t cells = box.num_cells();
  offset_.assign(cells + 1, 0);
  std::array<std::vector<int>, 3> axis;
  auto cover = [&](std::size_t a, auto &&visit) {
    for (int k = 0; k < 3; ++k) {
      axis[k].clear();
      if (k >= box.dim) {
        axis[k].push_back(0);
        continue;
      }
      const int n = box.cells[k];
      const int lo = static_cast<int>(std::floor(c.x[k][a] - c.radius[a]));
      const int hi = static_cast<int>(std::floor(c.x[k][a] + c.radius[a]));
      if (k == 1 && box.walls_y) {
        for (int q = std::max(lo, 0); q <= std::min(hi, n - 1); ++q)
          axis[k].push_back(q);
      } else if (hi - lo + 1 >= n) {
        for (int q = 0; q < n; ++q)
          axis[k].push_back(q);
      } else {
        for (int q = lo; q <= hi; ++q)
          axis[k].push_back(((q % n) + n) % n);
      }
    }
    for (const int z : axis[2])
      for (const int y : axis[1])
        for (const int x : axis[0])
          visit((static_cast<std::size_t>(z) * box.cells[1] + y) * box.cells[0] + x);
  };
  for (std::size_t a = 0; a < c.size(); ++a)
    cover(a, [&](std::size_t g) { ++offset_[g + 1]; });
  for (std::size_t g = 0; g < cells; ++g)
    offset_[g + 1] += offset_[g];
  list_.resize(offset_[cells]);
  std::vector<std::uint32_t> fill(offset_.begin(), offset_.end() - 1);
  for (std::size_t a = 0; a < c.size(); ++a)
    cover(a, [&](std::size_t g) { list_[fill[g]++] = static_cast<std::uint32_t>(a); });
}

bool ColloidCover::inside(const std::array<double, 3> &p) const {
  std::size_t g = 0;
  for (int k = box_.dim - 1; k >= 0; --k) {
    const int q = std::clamp(static_cast<int>(std::floor(p[k])), 0, box_.cells[k] - 1);
    g = g * static_cast<std::size_t>(box_.cells[k]) + static_cast<std::size_t>(q);
  }
  for (std::uint32_t j = offset_[g]; j < offset_[g + 1]; ++j) {
    const std::uint32_t a = list_[j];
    if (distance2(box_, p, position(c_, a)) < c_.radius[a] * c_.radius[a])
      return true;
  }
  return false;
}

} // namespace narrows::colloids
