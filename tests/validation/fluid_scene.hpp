// The MPCD fluid scene the validation tests start from (no force, no walls); each test adds
// the force and boundaries it measures with.
#pragma once

#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>

namespace narrows::validation {

inline scene::Scene fluid_scene(int dim, scene::Collision rule, double n, double dt,
                                double angle_deg, std::array<double, 3> size, std::uint64_t seed) {
  scene::Scene s;
  s.file = "(validation)";
  s.run.dimensions = dim;
  s.run.seed = seed;
  s.domain.size = size;
  s.fluid.collision = rule;
  s.fluid.density = n;
  s.fluid.dt = dt;
  s.fluid.angle_deg = angle_deg;
  return s;
}

} // namespace narrows::validation
