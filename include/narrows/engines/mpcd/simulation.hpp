// The MPCD simulation: state, the plan resolved once from the scene (plan.hpp), and the step: a
// list of stages built once from the plan (build_stages in simulation.cpp), each a line of the
// pipeline `narrows check`/`info` print and the call that runs it.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/packing.hpp"
#include "narrows/engines/mpcd/coupling/coupling.hpp"
#include "narrows/engines/mpcd/coupling/md_integrator.hpp"
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/cell_sort.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/engines/mpcd/kernels/thermostat.hpp"
#include "narrows/engines/mpcd/plan.hpp"
#include "narrows/engines/mpcd/work_balance.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace narrows::mpcd {

// A stage of the step: its line in the pipeline and its call (coupling.hpp).
using Stage = coupling::Stage;

class MpcdSimulation {
public:
  // Builds the slabs, the plan and, if `allocate`, this rank's cell grid and its part of the
  // initial state: the particles of its own cells (mpcd::init_fluid: ids 0..N-1, each drawn
  // from (seed, id), the same state on any number of ranks, zero total momentum) and the
  // colloids whose centres lie in its slab (colloids/ownership.hpp). Without it only the plan
  // exists (for `narrows info` and `check`). Throws bad_input if the scene cannot run on the ranks
  // of comm (check_ranks).
  MpcdSimulation(const scene::Scene &scene, MPI_Comm comm, bool allocate = true);
  MpcdSimulation(const MpcdSimulation &) = delete;
  MpcdSimulation &operator=(const MpcdSimulation &) = delete;

  // One MPCD step: every stage of the list in order, then the step counter advances.
  void advance();

  // Continues from a checkpoint: the fluid becomes `fluid` (any block of the particles; the
  // next advance() first sends them to their slab owners), the step counter `step`. For a
  // simulation built with allocate = false, this also builds this rank's cell grid.
  void restore(mpcd::Fluid &&fluid, std::int64_t step);
  // With [colloids], a restart also restores them: `all` holds every colloid; this rank keeps
  // those it owns.
  void restore_colloids(colloids::Colloids &&all);

  std::int64_t step() const { return step_; }
  double time() const { return static_cast<double>(step_) * scene_.fluid.dt; }
  // The step's stages in the order they run; the pipeline `check`/`info` print is this list.
  const std::vector<Stage> &stages() const { return stages_; }
  // The same, to add or take out a stage (a test of the list; an effect tried out before it
  // has a scene key). advance() runs whatever the list holds.
  std::vector<Stage> &stages() { return stages_; }
  const scene::Scene &scene() const { return scene_; }
  const mpcd::Box &box() const { return box_; }
  mpcd::Fluid &fluid() { return fluid_; }
  const mpcd::Fluid &fluid() const { return fluid_; }
  // The colloids this rank owns (those whose centres lie in its slab), in id order; empty
  // without [colloids].
  // What placement = "packing" reached (set when it packed the colloids at the start).
  const std::optional<colloids::PackingReport> &packing() const { return packing_; }
  colloids::Colloids &colloids() { return colloids_; }
  const colloids::Colloids &colloids() const { return colloids_; }
  // All colloids in id order, on every rank (collective): for observables and output.
  colloids::Colloids gather_colloids() const;
  // The spring contacts' history of every rank in key order, on every rank (collective; empty
  // without spring contacts).
  colloids::ContactHistory gather_contacts() const;
  // A checkpoint's contact history (all of it, every rank): each rank keeps the contacts of the
  // colloids it owns (after restore_colloids).
  void restore_contacts(colloids::ContactHistory &&all);
  // Bytes this rank sent for colloids (ghosts, their forces, migration) since the start.
  std::uint64_t colloid_bytes_sent() const;
  // Bytes this rank sent in fluid messages (particles migrating to the slab of their cell).
  std::uint64_t fluid_bytes_sent() const { return exchange_.bytes_sent(); }
  // The MD integrator with [colloids] (nullptr without).
  coupling::MdIntegrator *md() { return md_ ? &*md_ : nullptr; }
  // The no-slip coupling with coupling = "no-slip" (nullptr without).
  const coupling::NoSlipCoupling *no_slip() const { return no_slip_ ? &*no_slip_ : nullptr; }
  const MpcdPlan &plan() const { return plan_; }
  const mpcd::CellGrid &grid() const { return grid_; }
  MPI_Comm comm() const { return comm_; }
  const parallel::Slabs &slabs() const { return slabs_; }
  // Particles this rank sent to other ranks in the last step.
  std::size_t migrated_last_step() const { return strays_.index.size(); }

  // Work balance (work_balance.hpp). The counts of this rank since the start (or the restart).
  const WorkCounts &work() const { return work_; }
  // Moves the slab boundaries so that the work estimated per cell column is even, and the
  // fluid, the colloids and their contacts to their new owners (collective, between steps; the
  // results stay bitwise the same). Returns whether they moved. With `window_work` (every
  // rank's counted work over the last `window_steps` steps, the same on every rank) the
  // estimate of each slab's columns is scaled to what its rank counted; with `shares` (one per
  // rank, the same on every rank) rank r gets that share of the work (balanced_first_columns).
  bool balance_work(const std::vector<double> *window_work = nullptr, double window_steps = 0.0,
                    const std::vector<double> &shares = {});
  // The slabs given by their first columns (collective, the same on every rank; between steps).
  void set_slabs(const std::vector<int> &first_columns);
  // With domain.balance_every > 0, each check of the last balance_every steps: the max/mean
  // over the ranks of the counted work and of the busy time (the steps' wall time less their
  // messages and waiting), and whether the slabs moved then.
  struct BalanceCheck {
    std::int64_t step;
    double imbalance;
    double busy_imbalance;
    bool moved;
  };
  const std::vector<BalanceCheck> &balance_checks() const { return balance_checks_; }

private:
  void step_stages(); // the step itself; advance() adds the step and rank to its errors
  void build_stages();
  coupling::FluidStream stream_kernel() const;
  void migrate_to_owners(parallel::Reach reach = parallel::Reach::neighbours);
  void migrate_strays_and_bin_arrivals();
  void count_work();

  scene::Scene scene_;
  MPI_Comm comm_;
  mpcd::Box box_;
  parallel::Slabs slabs_;
  parallel::Exchange exchange_;
  MpcdPlan plan_;
  mpcd::Strays strays_;
  std::vector<int> stray_dest_;
  mpcd::Fluid fluid_;
  colloids::Colloids colloids_;
  std::optional<colloids::PackingReport> packing_;
  std::optional<coupling::MdIntegrator> md_;
  std::optional<coupling::NoSlipCoupling> no_slip_;
  coupling::NoColloids no_colloids_;
  coupling::Coupling *coupling_ = &no_colloids_; // md_, no_slip_ or no_colloids_
  mpcd::CellGrid grid_;
  mpcd::CollisionScratch collision_scratch_;
  mpcd::SortScratch sort_scratch_;
  mpcd::LayerSums layer_sums_;
  std::vector<Stage> stages_;
  std::int64_t step_ = 0;
  bool restored_ = false;    // the fluid is a checkpoint's blocks, not yet on its slabs
  WorkCounts work_, window_; // since the start, since the last balance check
  double window_busy_ = 0.0; // seconds of the steps since the last check, less their messages
  std::uint64_t bounced_ = 0, contact_updates_ = 0; // the coupling's totals at the last step
  std::vector<BalanceCheck> balance_checks_;
};

// The pipeline as `narrows check`/`info` print it: one numbered line per stage, in the order
// the step runs them.
std::vector<std::string> describe_pipeline(const std::vector<Stage> &stages);

mpcd::Box make_box(const scene::Scene &scene);

// The slabs of the scene on the ranks of comm; input_error (one line) if the box has too few
// cell columns for them or the scene cannot run on that many ranks (random-permute).
parallel::Slabs check_ranks(const scene::Scene &scene, MPI_Comm comm);

// Memory the run will need, without building it: bytes per particle times N plus cell arrays.
std::size_t estimate_memory(const scene::Scene &scene);
// The same for a given number of fluid particles (a packing's count is known only once packed).
std::size_t estimate_memory(const scene::Scene &scene, std::uint64_t particles);

// Number of fluid particles the scene creates (with [colloids]: the space they take excluded).
std::uint64_t particle_count(const scene::Scene &scene);

// The arrays of the fluid that travel with a particle, including its cell index (so a row
// moved within a rank keeps its binning; arrivals are binned again).
parallel::SoaView fluid_view(mpcd::Fluid &fluid);

} // namespace narrows::mpcd
