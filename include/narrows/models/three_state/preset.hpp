// Presets of Tabatabaei (2008) ch.2 for the kmc engine: what the dissertation derives for family 1
// (charge conserving, eq 2.5) and family 2 (ASEP with a binary internal state, eq 2.79/2.86), and
// whether the given rates satisfy the conditions the derivations need, with residuals.
//
// Two kinds of check are made. The dissertation's own equations (2.35-2.36, 2.93-2.94, 2.109-2.111,
// 2.114, 2.72-2.75) are evaluated as printed. Independently, the product measure pi of each
// fugacity is tested numerically against the condition those equations come from: the
// two-site generator G must map pi (x) pi into divergence form,
//   (G pi(x)pi)(a, b) = (d(a) - d(b)) pi(a) pi(b)               (eq 2.30 and 2.89-2.92),
// with d(vacancy) = 0 (then d(A), d(B) are F, F' of eq 2.33-2.34 for family 1 and -E, -E' of
// eq 2.93 for family 2), and the boundary sites must close the telescoping sum:
//   G_left pi = (<d> - d) pi,   G_right pi = (d - <d>) pi        (eq 2.31-2.32, 2.98-2.99).
// The residuals are the least-squares remainders of these equations.
#pragma once

#include "narrows/models/three_state/model.hpp"

#include <array>
#include <string>
#include <vector>

namespace narrows::three_state {

// One fugacity z and the product measure it defines.
struct Branch {
  double z = 0.0, nu = 0.0;
  std::array<double, 3> p{}; // P(n) for n = 0, 1, 2
  double rho_a = 0.0, rho_b = 0.0;
  double rho = 0.0;         // particles: rho_A + rho_B (both families)
  double sigma = 0.0;       // family 1: charge rho_A - rho_B (eq 2.27)
  double current = 0.0;     // stationary current of the preset's conserved charge (2.48 / 2.126)
  double current_247 = 0.0; // family 1: eq 2.47 (equal to 2.48 when 2.36 holds)
};

struct Residual {
  std::string what;
  double value = 0.0;
};

struct PresetReport {
  Preset preset = Preset::none;
  double ratio = 0.0;       // r (family 1, eq 2.35) or c (family 2)
  double f = 0.0, fp = 0.0; // F, F' (family 1, eq 2.33-2.34) or E, E' (family 2, eq 2.93)
  std::vector<Branch> branches;
  bool shock = false;                // two fugacities given
  double d1 = 0.0, d2 = 0.0;         // shock hopping rates to the left and to the right
  double v_s = 0.0;                  // shock velocity, Tabatabaei's sign: positive to the left
  double d_s = 0.0;                  // shock diffusion coefficient
  std::vector<Residual> residuals;   // every condition checked (0 when it holds)
  std::vector<std::string> lines;    // what the dissertation derives, for check/info/log
  std::vector<std::string> warnings; // conditions that fail, with their residuals
};

// The 24 rates of family 2 from the 15 parameters by the PT relations (eq 2.86).
std::array<double, 81> family2_rates(const std::array<double, 6> &h, const std::array<double, 9> &r,
                                     double c);

// Family 1's r (eq 2.35); 1 when no reaction rate is given.
double family1_ratio(const std::array<double, 81> &rates);

// The product measure of fugacity z for a preset (ratio = r or c).
std::array<double, 3> preset_marginal(Preset preset, double ratio, double z);

// The conserved charge a preset counts: family 1 C = 1 - n, family 2 C = particle number.
std::array<int, 3> preset_charge(Preset preset);

// State that carries no charge (the vacancy): 1 in family 1, 0 in family 2.
int vacancy_state(Preset preset);

struct BulkFit {
  std::array<double, 3> d{}; // d(vacancy) = 0
  double residual = 0.0;     // max |remainder| over the 9 pair states
};
BulkFit bulk_fit(const std::array<double, 81> &rates, const std::array<double, 3> &p, int vacancy);

// Remainder of the boundary condition of one end site (max |.| over the 3 states).
double boundary_residual(const std::array<double, 9> &site, const std::array<double, 3> &p,
                         const std::array<double, 3> &d, bool left);

// Rates of one end site that satisfy that condition exactly: net flows routed from the most
// probable state to the other two, each reverse rate equal to `coupling`.
std::array<double, 9> boundary_rates_for(const std::array<double, 3> &p,
                                         const std::array<double, 3> &d, bool left,
                                         double coupling);

// Fills what a preset derives into the model: charge (unless `keep_charge`), generated
// boundary rates, initial probabilities from the fugacities.
void apply_preset(Model &model, bool keep_charge, bool initial_given);

// The hydrodynamic flux of a preset as a function of its conserved density: family 1 the
// charge current eq 2.48 at sigma with rho = rho*(sigma) of eq 2.59 (eq 2.60); family 2 the
// particle current eq 2.126 at rho. `density` is sigma in [-1, 1] or rho in [0, 1].
double hydrodynamic_flux(const Model &model, double density);
// eq 2.59 solved for rho* in [|sigma|, 1].
double family1_rho_star(double sigma, double r);

// Everything the dissertation derives for the model's preset, checked.
PresetReport analyse(const Model &model);

} // namespace narrows::three_state
