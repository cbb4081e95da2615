// Names of the scene enums, as written in scene files and shown in messages.
#include "narrows/scene/scene.hpp"

#include <algorithm>
#include <numbers>

namespace narrows::scene {

const char *to_string(Engine e) {
  switch (e) {
  case Engine::mpcd:
    return "mpcd";
  case Engine::lgca:
    return "lgca";
  case Engine::kmc:
    return "kmc";
  case Engine::continuum:
    return "continuum";
  }
  return "unknown";
}

const char *to_string(Collision c) {
  switch (c) {
  case Collision::srd:
    return "srd";
  case Collision::at:
    return "at";
  case Collision::at_a:
    return "at+a";
  case Collision::random_permute:
    return "random-permute";
  case Collision::random_maxwell:
    return "random-maxwell";
  }
  return "unknown";
}

const char *to_string(LgcaModel m) {
  switch (m) {
  case LgcaModel::fhp_i:
    return "fhp-i";
  case LgcaModel::fhp_ii:
    return "fhp-ii";
  case LgcaModel::fhp_iii:
    return "fhp-iii";
  case LgcaModel::fhp_saturated:
    return "fhp-saturated";
  case LgcaModel::dhumieres_1d:
    return "dhumieres-1d";
  }
  return "unknown";
}

std::array<double, 3> colloid_acceleration(const Scene &s) {
  std::array<double, 3> g{0.0, 0.0, 0.0};
  if (!s.colloids)
    return g;
  g = s.colloids->gravity;
  if (s.body_force && s.body_force->kind == ForceKind::constant &&
      s.body_force->acts_on == DriveTarget::fluid_and_colloids)
    for (int k = 0; k < 3; ++k)
      g[k] += s.body_force->value[k]; // (0 + a is a: the same bits as gravity = a)
  return g;
}

double Colloids::max_radius() const {
  if (kinds.empty())
    return radius + 3.0 * radius_sd;
  double r = 0.0;
  for (const auto &k : kinds)
    r = std::max(r, k.radius);
  return r;
}

std::size_t Colloids::kind_of(std::uint64_t id) const {
  std::uint64_t end = 0;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    end += static_cast<std::uint64_t>(kinds[k].count);
    if (id < end)
      return k;
  }
  return kinds.empty() ? 0 : kinds.size() - 1;
}

double Colloids::mass_of_id(int dim, double density, std::uint64_t id, double r) const {
  if (kinds.empty())
    return mass_of(dim, density, r);
  const double m = kinds[kind_of(id)].mass;
  if (m > 0.0)
    return m;
  const double pi = std::numbers::pi;
  return density * (dim == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r);
}

double Colloids::mass_of(int dim, double density, double r) const {
  if (mass > 0.0)
    return mass;
  // Mass density of the colloid equal to the fluid's (Tabatabaei (2008) table 3.1: M = pi r^2 n).
  const double pi = std::numbers::pi;
  return density * (dim == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r);
}

} // namespace narrows::scene
