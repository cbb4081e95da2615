// The three-state lattice-gas model (Tabatabaei (2008) ch.2) as plain data: rates, boundaries,
// initial measure, preset. Below the scene in the layers (docs/architecture.md): the scene's
// [kmc] section is this struct (scene::Kmc), and the presets, theory and fluxes of this folder
// take it without knowing the scene.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::three_state {

// The three-state stochastic lattice gas of Tabatabaei (2008) ch.2, as the scene's [kmc] section
// (engine kmc) and the continuum engine's lattice-gas fluxes describe it (docs/scenes.md).
// States 0/1/2; pair codes c = 3 n_k + n_(k+1) (Tabatabaei's label i = c + 1). All rates are
// zero unless given.
enum class Boundary { open, periodic };

// Presets of Tabatabaei (2008) ch.2: family 1 (charge conserving, eq 2.5; states A = 0, vacancy =
// 1, B = 2) and family 2 (ASEP with binary internal state, eq 2.79; vacancy = 0, A = 1, B = 2).
enum class Preset { none, family1, family2 };
enum class Initial { product, shock };

struct Model {
  std::int64_t length = 0;
  Boundary boundary = Boundary::open;
  std::array<double, 81> rates{};        // [from pair code * 9 + to pair code]
  std::array<double, 9> left{}, right{}; // site 1 / site L: [from state * 3 + to state]
  Initial initial_kind = Initial::product;
  std::array<double, 3> initial{1.0, 0.0, 0.0}; // product measure (shock: left of the shock)
  std::array<double, 3> initial_right{};        // shock: P(n) right of the shock
  std::int64_t shock_site = 0;                  // shock: sites 1..shock_site use `initial`
  std::array<int, 3> charge{0, 1, 2};           // C(n) counted by the current (default C = n)
  double time = 0.0;                            // observed simulated time after warm-up
  double warmup = 0.0;
  std::int64_t replicas = 1;
  std::int64_t samples = 0; // shock position samples over the observed time (0 = none)

  Preset preset = Preset::none;
  double c = 0.0;                      // family 2: ratio of B to A (eq 2.81)
  std::vector<double> fugacity;        // preset: z, or [z_left, z_right] for a shock
  bool boundary_from_fugacity = false; // preset: left/right rates made to fit the fugacities
  double boundary_coupling = 1.0;      // base rate of those generated boundary rates
  // Refuse a scene whose expected tries per replica (slots x largest total rate x (warmup +
  // time)) exceed this: such a run would not end in a useful time. Raise it to run anyway.
  double max_tries = 1e12;
};

} // namespace narrows::three_state
