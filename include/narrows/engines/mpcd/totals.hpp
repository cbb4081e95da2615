// Conserved totals of an MPCD simulation, colloids included: momentum and energy.
#pragma once

#include "narrows/engines/mpcd/simulation.hpp"

#include <array>

namespace narrows::mpcd {

// Total momentum of fluid (mass 1) and colloids (collective; the same on every rank).
std::array<double, 3> total_momentum(const MpcdSimulation &sim);

// Total energy: kinetic energy of fluid and colloids plus the potential energy of the colloid
// interactions (gravity's work not included) (collective). Uses the MD force scratch, which the
// next step recomputes anyway.
double total_energy(MpcdSimulation &sim);

// The colloids' mean velocity in the frame co-moving with the centre of mass (Tabatabaei (2008) eq
// 4.8-4.10: v_c - P_t / (N_f m_f + N_c M_c)), averaged over the steps added (collective).
class SettlingSum {
public:
  void add(const MpcdSimulation &sim);
  std::array<double, 3> mean() const;

private:
  std::array<double, 3> sum_{0.0, 0.0, 0.0};
  long steps_ = 0;
};

} // namespace narrows::mpcd
