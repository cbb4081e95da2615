// The colloid species' table: every per-colloid field, once.
#include "narrows/colloids/colloids.hpp"

namespace narrows::colloids {

species::Table table(Colloids &c) {
  using namespace species;
  // Radius, mass, spin and orientation came into checkpoints later than the rest (added_later).
  // The trajectory writes radius and id once, not as series.
  constexpr unsigned held = migrates | ghost | checkpoint;
  Table t("colloids", c.dim);
  t.vector("position", c.x, everywhere)
      .vector("velocity", c.v, everywhere)
      .scalar("radius", c.radius, held | added_later)
      .scalar("mass", c.mass, held | added_later)
      // The spin a body has (z in 2D, all three in 3D) is stored; all three travel.
      .split("angular_velocity", c.omega, "xyz", c.dim == 2 ? 2 : 0, everywhere | added_later)
      .split("orientation", c.q, "wxyz", 0, everywhere | added_later, {1.0, 0.0, 0.0, 0.0})
      .scalar("id", c.id, held)
      .extra(c.extra);
  return t;
}

species::Table table(const Colloids &c) {
  species::Table t = table(const_cast<Colloids &>(c));
  t.read_only();
  return t;
}

void Colloids::resize(std::size_t n) { table(*this).resize(n); }

} // namespace narrows::colloids
