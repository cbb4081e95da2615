// J(rho) of the conservation law (see continuum/flux.hpp).
#include "narrows/engines/continuum/flux.hpp"

#include "narrows/models/three_state/preset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace narrows::continuum {

Flux::Flux(const scene::Continuum &model)
    : kind_(model.flux), c_(model.c), c_prime_(model.c_prime), v_cm_(model.v_cm),
      lattice_(model.lattice_gas) {}

double Flux::lattice_gas(double rho) const { return three_state::hydrodynamic_flux(lattice_, rho); }

double Flux::speed(double rho) const {
  switch (kind_) {
  case scene::ContinuumFlux::burgers:
    return rho;
  case scene::ContinuumFlux::colloid_chain:
    return 2.0 * c_ * rho + c_prime_ - v_cm_;
  default: {
    const double h = 1e-6;
    return (lattice_gas(rho + h) - lattice_gas(rho - h)) / (2.0 * h);
  }
  }
}

double Flux::max_speed(double lo, double hi) const {
  double m = std::max(std::abs(speed(lo)), std::abs(speed(hi)));
  const int n = 1024;
  for (int i = 1; i < n; ++i)
    m = std::max(m, std::abs(speed(lo + (hi - lo) * i / n)));
  return m;
}

std::string Flux::describe() const {
  char buf[320];
  switch (kind_) {
  case scene::ContinuumFlux::burgers:
    return "J(rho) = rho^2 / 2 (Burgers)";
  case scene::ContinuumFlux::colloid_chain:
    std::snprintf(buf, sizeof buf,
                  "J(rho) = rho (c rho + c' - v_cm), c = %g, c' = %g, v_cm = %g (sedimenting "
                  "colloid chain, Tabatabaei (2008) eq 5.3)",
                  c_, c_prime_, v_cm_);
    return buf;
  case scene::ContinuumFlux::tasep:
    std::snprintf(buf, sizeof buf,
                  "J(rho) = (p - q) rho (1 - rho) = %g rho (1 - rho) "
                  "(TASEP/ASEP, Tabatabaei (2008) eq 5.1)",
                  three_state::hydrodynamic_flux(lattice_, 0.5) * 4.0);
    return buf;
  case scene::ContinuumFlux::family1:
    std::snprintf(buf, sizeof buf,
                  "J(sigma) = charge current of family 1 (eq 2.48) at rho*(sigma) of eq 2.59 "
                  "(eq 2.60), r = %g; J(-1, 0, 1) = %g, %g, %g",
                  three_state::family1_ratio(lattice_.rates), lattice_gas(-1.0), lattice_gas(0.0),
                  lattice_gas(1.0));
    return buf;
  case scene::ContinuumFlux::family2:
    std::snprintf(buf, sizeof buf,
                  "J(rho) = particle current of family 2 (eq 2.126), c = %g: %g rho (1 - rho)",
                  lattice_.c, three_state::hydrodynamic_flux(lattice_, 0.5) * 4.0);
    return buf;
  }
  return {};
}

} // namespace narrows::continuum
