// The colloid species as a structure of arrays (seed 000 §3.4): position, velocity, angular
// velocity (kept for the no-slip and contact models of later issues), radius, mass, global id.
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
  std::vector<double> radius, mass;
  std::vector<std::uint64_t> id;

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n) {
    for (int k = 0; k < 3; ++k) {
      x[k].resize(k < dim ? n : 0);
      v[k].resize(k < dim ? n : 0);
      omega[k].resize(n);
    }
    radius.resize(n);
    mass.resize(n);
    id.resize(n);
  }
};

// Volume (2D: area) of a colloid of radius r: pi r^2 or 4/3 pi r^3.
double colloid_volume(int dim, double r);

} // namespace narrows::colloids
