// The colloid species as a structure of arrays (Tabatabaei (2008) §3.4): position, velocity,
// angular velocity and orientation (no-slip colloids spin), radius, mass, global id.
#pragma once

#include "narrows/species/table.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Between MPCD steps a rank holds the colloids it owns (ownership.hpp), in id order; within a
// step ghost copies of other ranks' colloids follow them (ghosts.hpp). Every field is declared in
// table() (colloids.cpp); what moves, copies, stores or gathers whole rows goes through it.
struct Colloids {
  int dim = 2;
  std::array<std::vector<double>, 3> x, v, omega; // components k < dim (omega: all 3, zero)
  // Orientation as a unit quaternion (w, x, y, z): the rotation from the initial orientation,
  // advanced by omega (no-slip colloids spin; MD colloids keep the identity). In 2D a rotation
  // by theta about z is (cos theta/2, 0, 0, sin theta/2).
  std::array<std::vector<double>, 4> q;
  std::vector<double> radius, mass;
  std::vector<std::uint64_t> id;
  species::Extra extra; // fields added at run time (none in a plain run)

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n); // every field; new rows: at rest, the identity orientation
};

// The colloid species' fields, one line each (the checkpoint's /particles/colloids/...).
species::Table table(Colloids &c);
// The same for reading only (gathering, writing).
species::Table table(const Colloids &c);

// Volume (2D: area) of a colloid of radius r: pi r^2 or 4/3 pi r^3.
double colloid_volume(int dim, double r);

} // namespace narrows::colloids
