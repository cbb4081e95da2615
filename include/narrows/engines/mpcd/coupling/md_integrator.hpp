// MD of colloids and fluid (Tabatabaei (2008) §3.4.5): over one collision step dt, k sub-steps of
// velocity Verlet with tau_MD = dt / k for the colloids and the fluid particles near them, with
// the forces of forces.hpp. Each rank moves the colloids it owns (ownership.hpp) with ghost
// copies of the others it can meet (ghosts.hpp). Its stages in the MPCD step (the hooks of
// coupling.hpp), in order:
// before_stream:
//   take_near_fluid  forces now; each colloid's largest path; the ghosts for the step; a copy
//                    of the fluid that may meet a colloid this step (near_fluid.hpp says how
//                    it is chosen)
// (the engine streams all fluid the whole step, exactly, with the kernel its plan chose)
// after_stream:
//   substeps         velocity Verlet of the owned colloids and the near copies (these stream by
//                    the same kernel between the kicks); the ghosts follow their owners
//   put_back_near_fluid  the near copies replace their rows of the fluid
//   check_paths      invariant_error if a colloid went further than assumed (a missed pair) or
//                    a near particle left the region whose colloids this rank held
//   hand_over        the ghosts go; colloids that left the slab go to their new owners
// All calls are collective over the slabs' communicator.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/forces.hpp"
#include "narrows/colloids/ghosts.hpp"
#include "narrows/engines/mpcd/coupling/coupling.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::coupling {

struct MdParams {
  double tau = 0.1 / 15; // MD time step
  int substeps = 15;
  double fluid_accel = 0.0; // largest body-force acceleration of a fluid particle
};

class MdIntegrator final : public Coupling {
public:
  MdIntegrator(const MdParams &params, const colloids::ForceParams &forces, const mpcd::Box &box,
               const parallel::Slabs &slabs);

  Stages before_stream(const StageContext &at) override;
  Stages after_stream(const StageContext &at) override;

  void take_near_fluid(const mpcd::Fluid &fluid, colloids::Colloids &colloids);
  void substeps(colloids::Colloids &colloids, const FluidStream &stream);
  void put_back_near_fluid(mpcd::Fluid &fluid) const;
  void check_paths(const colloids::Colloids &colloids) const;
  void hand_over(colloids::Colloids &colloids);
  // The colloids to their owners under `slabs` (collective, between steps).
  void set_slabs(const parallel::Slabs &slabs, colloids::Colloids &colloids) override;

  // The potential energy of fluid and colloids (those this rank owns, between steps), summed
  // over the ranks (collective).
  colloids::PotentialEnergy potential_energy(const mpcd::Fluid &fluid,
                                             colloids::Colloids &colloids);
  const MdParams &params() const { return params_; }
  // Bytes this rank sent for colloids (ghosts, reverse, migration) since the start.
  std::uint64_t bytes_sent() const { return ghosts_.bytes_sent() + migration_.bytes_sent(); }

private:
  void kick(mpcd::Fluid &fluid, colloids::Colloids &colloids) const;

  MdParams params_;
  mpcd::Box box_;
  int dim_;
  parallel::Slabs slabs_;
  colloids::ForceField forces_;
  colloids::ColloidGhosts ghosts_;
  parallel::Exchange migration_;
  std::vector<double> margin_;            // per colloid: its largest possible path this step
  std::vector<std::uint32_t> near_index_; // local fluid particles taking part in the sub-steps
  std::vector<std::uint8_t> near_flag_;
  mpcd::Fluid near_;                         // their copy during the sub-steps
  std::array<std::vector<double>, 3> start_; // owned colloid positions at the start of the step
};

} // namespace narrows::coupling
