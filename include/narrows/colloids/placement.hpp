// The geometry of placing colloids (minimum-image distances in the box) and the test "inside a
// colloid" used to keep the initial fluid out of them. Placing a scene's colloids (radii, masses,
// positions) is the MPCD engine's: engines/mpcd/colloid_placement.hpp.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Minimum-image squared distance between a and b (periodic axes wrapped, the wall axis y not).
inline double distance2(const mpcd::Box &box, const std::array<double, 3> &a,
                        const std::array<double, 3> &b) {
  double r2 = 0.0;
  for (int k = 0; k < box.dim; ++k) {
    double d = a[k] - b[k];
    if (!(k == 1 && box.walls_y)) {
      const double L = box.length[k];
      if (d > 0.5 * L)
        d -= L;
      else if (d < -0.5 * L)
        d += L;
    }
    r2 += d * d;
  }
  return r2;
}

// The centre of colloid i (z = 0 in 2D).
inline std::array<double, 3> position(const Colloids &c, std::size_t i) {
  return {c.x[0][i], c.x[1][i], c.dim == 3 ? c.x[2][i] : 0.0};
}

// True if p lies within distance r_a of the centre of a colloid a (minimum image along periodic
// axes).
bool inside_any(const Colloids &c, const mpcd::Box &box, const std::array<double, 3> &p);

// The colloids that overlap each collision cell of the box (cells of size 1), for keeping the
// initial fluid out of them in O(colloids per cell) per test.
class ColloidCover {
public:
  ColloidCover(const Colloids &c, const mpcd::Box &box);
  // The same as inside_any(c, box, p).
  bool inside(const std::array<double, 3> &p) const;

private:
  const Colloids &c_;
  mpcd::Box box_;
  std::vector<std::uint32_t> offset_, list_; // colloids of cell g: list_[offset_[g], offset_[g+1])
};

} // namespace narrows::colloids
