// Test helper: the 2D SRD fluid of Tabatabaei (2008) ch.3-4 (n = 10, tau_c = 0.1, alpha = 90 deg)
// with colloids, in a periodic box or a channel.
#pragma once

#include "narrows/scene/scene.hpp"

#include <cstdint>

namespace narrows::testing {

inline scene::Scene srd_colloid_scene(double lx, double ly, bool walls, std::uint64_t seed,
                                      const scene::Colloids &colloids) {
  scene::Scene s;
  s.run.dimensions = 2;
  s.run.seed = seed;
  s.domain.size = {lx, ly, 0.0};
  s.fluid.collision = scene::Collision::srd;
  s.fluid.density = 10.0;
  s.fluid.dt = 0.1;
  s.fluid.angle_deg = 90.0;
  if (walls)
    s.walls = scene::Walls{};
  s.colloids = colloids;
  return s;
}

} // namespace narrows::testing
