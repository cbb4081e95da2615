// The flux J(rho) of the 1D conservation law rho_t + J(rho)_x = D rho_xx: Burgers, the
// lattice-gas fluxes of Tabatabaei (2008) ch.2 (taken from the kmc presets, kmc/preset.hpp: family
// 1's eq 2.48 with rho*(sigma) of eq 2.59, i.e. eq 2.60; family 2's eq 2.126; TASEP/ASEP as family
// 2 without B) and the sedimenting colloid chain of Tabatabaei (2008) ch.5 (eq 5.3).
#pragma once

#include "narrows/scene/scene.hpp"

#include <string>

namespace narrows::continuum {

class Flux {
public:
  explicit Flux(const scene::Continuum &model);

  // J(rho): a switch on the kind, no virtual call.
  double operator()(double rho) const {
    switch (kind_) {
    case scene::ContinuumFlux::burgers:
      return 0.5 * rho * rho;
    case scene::ContinuumFlux::colloid_chain:
      return rho * (c_ * rho + c_prime_ - v_cm_);
    default:
      return lattice_gas(rho);
    }
  }
  // J'(rho): exact for Burgers and the colloid chain, a central difference (step 1e-6, error
  // ~1e-12 J''') for the lattice gases.
  double speed(double rho) const;
  // The largest |J'| over [lo, hi] (sampled at 1025 points and the ends): the CFL bound,
  // which holds for the whole run because the solution stays within the range of its initial
  // and boundary data (maximum principle of scalar conservation laws).
  double max_speed(double lo, double hi) const;
  // The formula with its coefficients, for check/info and the log.
  std::string describe() const;
  scene::ContinuumFlux kind() const { return kind_; }

private:
  double lattice_gas(double rho) const;

  scene::ContinuumFlux kind_;
  double c_ = 0.0, c_prime_ = 0.0, v_cm_ = 0.0;
  scene::Kmc lattice_; // the preset's rates for three_state::hydrodynamic_flux
};

} // namespace narrows::continuum
