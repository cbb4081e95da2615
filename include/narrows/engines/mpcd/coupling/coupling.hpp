// The coupling of colloids and fluid as the MPCD step sees it: the stages a coupling adds at
// four points of the step. Three couplings implement it: MD colloids (md_integrator.hpp),
// no-slip colloids (no_slip.hpp) and NoColloids below.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/parallel/slabs.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace narrows::coupling {

// One stage of the MPCD step: the line `narrows check`/`info` print for it and what it does,
// called once per step with the step number. The step is its list of stages and nothing else,
// so the pipeline a user reads is the one that runs.
struct Stage {
  std::string name;
  std::function<void(std::uint64_t step)> run;
};
using Stages = std::vector<Stage>;

// Streams fluid by tau (walls and body force exact); chosen once by the engine's plan.
using FluidStream = std::function<void(mpcd::Fluid &, double tau)>;

// What the engine gives a coupling's stages: its state (which outlives the stages, so they keep
// these references), its streaming kernel, and the words for what only the scene knows.
struct StageContext {
  mpcd::Fluid &fluid;
  colloids::Colloids &colloids;
  mpcd::CellGrid &grid;
  // The last collision's scratch: its v2_max, and the ghost particles' share of the sums
  // (within_collide: also the cells' records that MPC-AT+a's particle pass reads).
  mpcd::CollisionScratch &collision;
  FluidStream stream;
  std::string stream_name;   // the streaming stage's line
  std::string colloids_name; // the colloids, their sizes and forces as the scene gives them
};

// Each hook returns the stages the coupling runs at that point of the step, in order (none: an
// empty list). The engine calls the hooks once, when it builds its stage list, not every step.
class Coupling {
public:
  virtual ~Coupling() = default;
  // Before the fluid streams over the whole step.
  virtual Stages before_stream(const StageContext &) { return {}; }
  // After it streamed, before the grid shift.
  virtual Stages after_stream(const StageContext &) { return {}; }
  // After the fluid is binned into the shifted cells (on its slab owners), before the walls'
  // virtual particles and the collision. Not reached by the random solvent that has no cells.
  virtual Stages after_bin(const StageContext &) { return {}; }
  // Within the collision, before the thermostat and the sort: MPC-AT+a collided the cells and
  // has not yet written the particles' new velocities (a stage may add a velocity change to
  // cells through the scratch: CollisionScratch::shift_offset); the other rules have collided
  // (and permuted) already.
  virtual Stages within_collide(const StageContext &) { return {}; }
  // Between steps (no ghost rows): the slabs move (work balance, simulation.hpp); the colloids
  // this rank owns, and what travels with them, go to their owners under `slabs` (collective).
  virtual void set_slabs(const parallel::Slabs &, colloids::Colloids &) {}
};

// A fluid without colloids: the step has no coupling stages.
class NoColloids final : public Coupling {};

} // namespace narrows::coupling
