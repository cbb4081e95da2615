// The grid of unit cells that finds the colloid holding a point.
#include "narrows/colloids/colloid_lookup.hpp"

#include "narrows/colloids/pair_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::colloids {

void ColloidLookup::build(const Colloids &c, const mpcd::Box &box, int first_column, int columns,
                          double extent) {
  box_ = box;
  const int L = box.cells[0];
  const int e = static_cast<int>(std::ceil(extent)) + 1;
  if (columns + 2 * e >= L) {
    lo_ = 0;
    nx_ = L;
  } else {
    lo_ = ((first_column - e) % L + L) % L;
    nx_ = columns + 2 * e;
  }
  ny_ = box.cells[1];
  nz_ = box.dim == 3 ? box.cells[2] : 1;
  head_.assign(static_cast<std::size_t>(nx_) * ny_ * nz_, -1);
  next_.clear();
  row_.clear();
  const int dim = box.dim;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double r = c.radius[a];
    int from[3] = {0, 0, 0}, to[3] = {0, 0, 0};
    for (int k = 0; k < dim; ++k) {
      from[k] = static_cast<int>(std::floor(c.x[k][a] - r));
      to[k] = static_cast<int>(std::floor(c.x[k][a] + r));
      if (k == 1 && box.walls_y) {
        from[k] = std::max(from[k], 0);
        to[k] = std::min(to[k], ny_ - 1);
      } else if (to[k] - from[k] + 1 >= box.cells[k]) { // wider than the box: every cell
        from[k] = 0;
        to[k] = box.cells[k] - 1;
      }
    }
    for (int i = from[0]; i <= to[0]; ++i) {
      const int col = ((i % L) + L) % L;
      const int ix = ((col - lo_) % L + L) % L;
      if (ix >= nx_)
        continue;
      for (int j = from[1]; j <= to[1]; ++j) {
        const int iy = ((j % ny_) + ny_) % ny_;
        for (int l = from[2]; l <= to[2]; ++l) {
          const int iz = ((l % nz_) + nz_) % nz_;
          const std::size_t cell = ix + static_cast<std::size_t>(nx_) * (iy + ny_ * iz);
          next_.push_back(head_[cell]);
          row_.push_back(static_cast<int>(a));
          head_[cell] = static_cast<int>(row_.size() - 1);
        }
      }
    }
  }
}

long ColloidLookup::inside_listed(const Colloids &c, const double *p, int cell) const {
  long best = -1;
  for (int e = head_[static_cast<std::size_t>(cell)]; e >= 0; e = next_[e]) {
    const auto a = static_cast<std::size_t>(row_[e]);
    double r2 = 0.0;
    for (int k = 0; k < box_.dim; ++k) {
      double d = p[k] - c.x[k][a];
      if (!(k == 1 && box_.walls_y))
        d = minimum_image(d, box_.length[k]);
      r2 += d * d;
    }
    if (r2 < c.radius[a] * c.radius[a] && (best < 0 || c.id[a] < c.id[best]))
      best = static_cast<long>(a);
  }
  return best;
}

} // namespace narrows::colloids
