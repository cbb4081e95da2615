// Collision tables generated from the FHP rules, and their Boltzmann viscosities.
#include "narrows/engines/lgca/fhp_model.hpp"

#include "narrows/core/error.hpp"

#include <bit>
#include <cmath>
#include <map>
#include <vector>

namespace narrows::lgca {

namespace {

constexpr std::uint8_t moving_mask = 0x3F;

// Rotation of the moving particles by k * 60 degrees; the rest particle stays.
std::uint8_t rotate(std::uint8_t s, int k) {
  const unsigned m = s & moving_mask;
  const unsigned r = ((m << k) | (m >> (6 - k))) & moving_mask;
  return static_cast<std::uint8_t>(r | (s & rest_bit));
}

bool head_on_pair(unsigned m) { return m == 0x09 || m == 0x12 || m == 0x24; }
bool symmetric_triple(unsigned m) { return m == 0x15 || m == 0x2A; }

// Whether state s takes part in the collisions of model m (s is a state of the model).
bool collides(FhpModel model, std::uint8_t s) {
  const unsigned m = s & moving_mask;
  switch (model) {
  case FhpModel::fhp_i:
    return head_on_pair(m) || symmetric_triple(m);
  case FhpModel::fhp_ii: {
    if (head_on_pair(m) || symmetric_triple(m))
      return true; // with or without a rest spectator
    const bool rest = (s & rest_bit) != 0;
    if (rest && std::popcount(m) == 1)
      return true; // rest + i -> {i-1, i+1}
    for (int i = 0; i < 6; ++i)
      if (!rest && m == ((1u << ((i + 1) % 6)) | (1u << ((i + 5) % 6))))
        return true; // {i-1, i+1} -> rest + i
    return false;
  }
  case FhpModel::fhp_iii:
  case FhpModel::fhp_saturated:
    return true; // groups of one member map to themselves anyway
  }
  return false;
}

} // namespace

const char *to_string(FhpModel m) {
  switch (m) {
  case FhpModel::fhp_i:
    return "fhp-i";
  case FhpModel::fhp_ii:
    return "fhp-ii";
  case FhpModel::fhp_iii:
    return "fhp-iii";
  case FhpModel::fhp_saturated:
    return "fhp-saturated";
  }
  return "?";
}

int links(FhpModel m) { return m == FhpModel::fhp_ii || m == FhpModel::fhp_iii ? 7 : 6; }

int mass(std::uint8_t s) { return std::popcount(static_cast<unsigned>(s)); }

std::array<int, 2> momentum_units(std::uint8_t s) {
  // c_i in units (1/2, sqrt(3)/2): (2, 0), (1, 1), (-1, 1), (-2, 0), (-1, -1), (1, -1).
  static constexpr int cx[6] = {2, 1, -1, -2, -1, 1}, cy[6] = {0, 1, 1, 0, -1, -1};
  std::array<int, 2> p{0, 0};
  for (int i = 0; i < 6; ++i)
    if (s >> i & 1) {
      p[0] += cx[i];
      p[1] += cy[i];
    }
  return p;
}

std::uint8_t bounce_back(std::uint8_t s) { return rotate(s, 3); }

CollisionTable make_collision_table(FhpModel model) {
  CollisionTable t;
  t.model = model;
  for (int s = 0; s < 128; ++s)
    t.out[0][s] = t.out[1][s] = static_cast<std::uint8_t>(s);
  const int states = 1 << links(model);
  // Groups of the colliding states by (mass, momentum), members in increasing order.
  std::map<std::array<int, 3>, std::vector<std::uint8_t>> groups;
  for (int s = 0; s < states; ++s) {
    const auto st = static_cast<std::uint8_t>(s);
    if (!collides(model, st))
      continue;
    const auto p = momentum_units(st);
    groups[{mass(st), p[0], p[1]}].push_back(st);
  }
  for (const auto &[key, members] : groups) {
    if (members.size() < 2)
      continue;
    const auto in_group = [&](std::uint8_t x) {
      for (const auto m : members)
        if (m == x)
          return true;
      return false;
    };
    for (std::size_t j = 0; j < members.size(); ++j) {
      const std::uint8_t s = members[j];
      const std::uint8_t plus = rotate(s, 1), minus = rotate(s, 5);
      if (plus != s && in_group(plus) && in_group(minus)) {
        t.out[0][s] = plus;
        t.out[1][s] = minus;
        continue;
      }
      std::vector<std::uint8_t> others;
      for (const auto m : members)
        if (m != s)
          others.push_back(m);
      if (others.size() > 2)
        throw Error(ExitCode::other, std::string("collision table of ") + to_string(model) +
                                         ": a group without rotation symmetry has more than "
                                         "three members (one chirality bit cannot choose)");
      t.out[0][s] = others.front();
      t.out[1][s] = others.back();
    }
  }
  return t;
}

double shear_relaxation_rate(const CollisionTable &table, double d) {
  const int b = links(table.model);
  // J_ij = sum_s P(s) (s_j - d) / (d (1 - d)) sum_chirality 1/2 (s'_i - s_i), applied to Q.
  std::array<double, 7> q{};
  for (int i = 0; i < 6; ++i) {
    const double cx = std::cos(M_PI * i / 3.0);
    q[i] = cx * cx - 0.5;
  }
  std::array<double, 7> jq{};
  for (int s = 0; s < (1 << b); ++s) {
    double p = 1.0, wq = 0.0;
    for (int j = 0; j < b; ++j) {
      const int n = s >> j & 1;
      p *= n ? d : 1.0 - d;
      wq += (n - d) / (d * (1.0 - d)) * q[j];
    }
    for (int chir = 0; chir < 2; ++chir) {
      const int s2 = table.out[chir][s];
      for (int i = 0; i < b; ++i)
        jq[i] += 0.5 * p * wq * static_cast<double>((s2 >> i & 1) - (s >> i & 1));
    }
  }
  return -jq[0] / q[0];
}

double table_viscosity(const CollisionTable &table, double d) {
  return 1.0 / (4.0 * shear_relaxation_rate(table, d)) - 0.125;
}

double boltzmann_viscosity(FhpModel m, double d) {
  const double e = 1.0 - d;
  switch (m) {
  case FhpModel::fhp_i:
    return 1.0 / (12.0 * d * e * e * e) - 0.125;
  case FhpModel::fhp_ii:
    return 1.0 / (28.0 * d * e * e * e * (1.0 - 4.0 * d / 7.0)) - 0.125;
  case FhpModel::fhp_iii:
    return 1.0 / (28.0 * d * e * (1.0 - 8.0 * d * e / 7.0)) - 0.125;
  case FhpModel::fhp_saturated:
    return 1.0 / (12.0 * d * e * (1.0 + 2.0 * d * e)) - 0.125;
  }
  return 0.0;
}

} // namespace narrows::lgca
