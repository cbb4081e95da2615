// The colloid species as a structure of arrays (seed 000 §3.4): position, velocity, angular
// velocity and orientation (no-slip colloids spin), radius, mass, global id.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Between MPCD steps a rank holds the colloids it owns (ownership.hpp), in id order; within a
// step ghost copies of other ranks' colloids follow them (ghosts.hpp).
struct Colloids {
  int dim = 2;
  std::array<std::vector<double>, 3> x, v, omega; // components k < dim (omega: all 3, zero)
  // Orientation as a unit quaternion (w, x, y, z): the rotation from the initial orientation,
  // advanced by omega (no-slip colloids spin; MD colloids keep the identity). In 2D a rotation
  // by theta about z is (cos theta/2, 0, 0, sin theta/2).
  std::array<std::vector<double>, 4> q;
  std::vector<double> radius, mass;
  std::vector<std::uint64_t> id;

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n) {
    for (int k = 0; k < 3; ++k) {
      x[k].resize(k < dim ? n : 0);
      v[k].resize(k < dim ? n : 0);
      omega[k].resize(n);
    }
    q[0].resize(n, 1.0); // new rows: the identity
    for (int k = 1; k < 4; ++k)
      q[k].resize(n, 0.0);
    radius.resize(n);
    mass.resize(n);
    id.resize(n);
  }
};

// Volume (2D: area) of a colloid of radius r: pi r^2 or 4/3 pi r^3.
double colloid_volume(int dim, double r);

} // namespace narrows::colloids
