// Conserved totals of an MPCD simulation, colloids included: momentum and energy.
#pragma once

#include "narrows/engine/mpcd_simulation.hpp"

#include <array>

namespace narrows::engine {

// Total momentum of fluid (mass 1) and colloids (collective; the same on every rank).
std::array<double, 3> total_momentum(const MpcdSimulation &sim);

// Total energy: kinetic energy of fluid and colloids plus the potential energy of the colloid
// interactions (gravity's work not included) (collective). Uses the MD force scratch, which the
// next step recomputes anyway.
double total_energy(MpcdSimulation &sim);

} // namespace narrows::engine
