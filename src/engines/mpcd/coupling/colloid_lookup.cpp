// The grid of unit cells that finds the colloid holding a point.
#include "narrows/engines/mpcd/coupling/colloid_lookup.hpp"

#include "narrows/colloids/pair_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::coupling {

using namespace narrows::colloids;

void ColloidLookup::build(const Colloids &c, const mpcd::Box &box, int first_column, int columns,
                          double extent) {
  box_ = box;
  const int S = box.dim == 2 ? 2 : 1; // lookup cells per unit length
  per_unit_ = S;
  const int L = S * box.cells[0];
  lx_ = L;
  const int e = static_cast<int>(std::ceil(extent)) + 1;
  if (columns + 2 * e >= box.cells[0]) {
    lo_ = 0;
    nx_ = L;
  } else {
    lo_ = ((S * (first_column - e)) % L + L) % L;
    nx_ = S * (columns + 2 * e);
  }
  const int cells[3] = {L, S * box.cells[1], box.dim == 3 ? S * box.cells[2] : 1};
  ny_ = cells[1];
  nz_ = cells[2];
  head_.assign(static_cast<std::size_t>(nx_) * ny_ * nz_, -1);
  listed_.assign(head_.size(), 0);
  entries_.clear();
  discs_.resize(c.size());
  const int dim = box.dim;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double r = c.radius[a], r2 = r * r;
    const double X[3] = {c.x[0][a], c.x[1][a], dim == 3 ? c.x[2][a] : 0.0};
    discs_[a] = {{X[0], X[1], X[2]}, r2};
    int from[3] = {0, 0, 0}, to[3] = {0, 0, 0};
    bool whole[3] = {false, false, false}; // every cell along this axis (distance not measured)
    for (int k = 0; k < dim; ++k) {
      from[k] = static_cast<int>(std::floor((c.x[k][a] - r) * S));
      to[k] = static_cast<int>(std::floor((c.x[k][a] + r) * S));
      if (k == 1 && box.walls_y) {
        from[k] = std::max(from[k], 0);
        to[k] = std::min(to[k], ny_ - 1);
      } else if (to[k] - from[k] + 1 >= cells[k]) { // wider than the box: every cell
        from[k] = 0;
        to[k] = cells[k] - 1;
        whole[k] = true;
      }
    }
    // Squared distance from the centre to the interval [i, i + 1) / S along axis k (i
    // unwrapped, as from[k] .. to[k]): a cell at r or beyond holds no point inside (the margin
    // covers rounding).
    const double h = 1.0 / S;
    const auto gap2 = [&](int k, int i) {
      if (whole[k])
        return 0.0;
      const double q = std::clamp(X[k], i * h, (i + 1) * h) - X[k];
      return q * q;
    };
    const double reach2 = r2 * (1.0 + 1e-9);
    // Rows (y) outside, columns (x) inside: a row's cells lie next to each other in head_ and
    // listed_. (A cell's list holds the same rows in the same order whatever the order within
    // one colloid: they come from the colloids in row order.)
    column_gap2_.clear();
    column_index_.clear();
    for (int i = from[0]; i <= to[0]; ++i) {
      const int ix = wrap_index(wrap_index(i, L) - lo_, L);
      column_gap2_.push_back(gap2(0, i));
      column_index_.push_back(ix < nx_ ? ix : -1);
    }
    const std::size_t columns_here = column_index_.size();
    for (int l = from[2]; l <= to[2]; ++l) {
      const double dl = dim == 3 ? gap2(2, l) : 0.0;
      const int iz = wrap_index(l, nz_);
      for (int j = from[1]; j <= to[1]; ++j) {
        const double dj = gap2(1, j);
        const std::size_t row = static_cast<std::size_t>(nx_) * (wrap_index(j, ny_) + ny_ * iz);
        for (std::size_t q = 0; q < columns_here; ++q) {
          // (the x, y, z terms added in that order, as the test was made before)
          if (column_index_[q] < 0 || (column_gap2_[q] + dj) + dl >= reach2)
            continue;
          const std::size_t cell = row + static_cast<std::size_t>(column_index_[q]);
          entries_.push_back({static_cast<int>(a), head_[cell]});
          head_[cell] = static_cast<int>(entries_.size() - 1);
          listed_[cell] = 1;
        }
      }
    }
  }
}

std::size_t ColloidLookup::listed_block(const double *x, const double *y, const double *z,
                                        std::size_t m, std::uint32_t *found,
                                        std::int32_t *found_cell) const {
  int cell[block];
  const double S = per_unit_;
  const int lx = lx_, lo = lo_, nx = nx_, ny = ny_, nz = nz_;
  for (std::size_t j = 0; j < m; ++j) { // as cell_of()
    int ix = std::min(static_cast<int>(x[j] * S), lx - 1) - lo;
    ix += ix < 0 ? lx : 0;
    const int iy = std::clamp(static_cast<int>(y[j] * S), 0, ny - 1);
    const int iz = z ? std::clamp(static_cast<int>(z[j] * S), 0, nz - 1) : 0;
    const int c = ix + nx * (iy + ny * iz);
    cell[j] = ix < nx ? c : -1;
  }
  std::size_t k = 0;
  for (std::size_t j = 0; j < m; ++j) {
    found[k] = static_cast<std::uint32_t>(j);
    found_cell[k] = cell[j];
    k += (cell[j] >= 0) & (listed_[static_cast<std::size_t>(cell[j] < 0 ? 0 : cell[j])] != 0);
  }
  return k;
}

} // namespace narrows::coupling
