// No-slip colloids in the MPCD fluid (Kanehl (thesis) §4.2.1): rigid disks (2D) and spheres (3D)
// that move by their own velocity U and spin Omega, bounce fluid particles back at their surface
// with the rigid-body velocity there, and fill the cells they cut with ghost particles that
// take part in the collision. Every momentum and angular momentum the fluid loses goes to the
// colloids (summed in fixed point, so the result does not depend on the order of particles or
// on the number of ranks). Its stages in the MPCD step (the hooks of coupling.hpp), in order:
// before_stream:
//   move_colloids          orientation turned by Omega dt (the step's starting spin); gravity
//                          kick U += g dt (springs: the force M g in each sub-step, so that a
//                          colloid resting on others does not bounce each step); ghosts for the
//                          step; every colloid moves
//                          U dt (contacts = "none"), by event-driven rough hard spheres
//                          (contacts = "hard", hard_spheres.hpp) or in velocity-Verlet
//                          sub-steps under linear springs with Coulomb friction (contacts =
//                          "spring", springs.hpp; the ghosts follow their owners each sub-step)
// (the engine streams all fluid the whole step with the kernel its plan chose)
// after_stream:
//   bounce_back            every fluid particle that ended inside a colloid: back half the
//                          interval, onto the surface, v' = 2 (U + Omega x r) - v (eq 4.15),
//                          forward half the interval; again with halved intervals while it
//                          ends inside one (Padding et al.); the impulses go to the colloids
//                          (eq 4.16-4.17 with the sign that conserves momentum)
// (the engine shifts the grid and bins the fluid)
// after_bin:
//   add_ghost_particles    in each cell cut by a colloid's surface, at the fluid density, at
//                          random points inside the colloid, velocity U + Omega x r + a
//                          Maxwell-Boltzmann draw at kT (eq 4.18); each (colloid, cell) pair's
//                          ghosts enter the collision as one group of sums (grid.groups, see
//                          ghost_particles.cpp), exact in distribution
// (the engine collides; MPC-AT+a its cells, not yet its particles)
// within_collide:
//   take_back_ghost_particles  their momentum and angular momentum change to the colloids;
//                          they leave the cell sums
// The impulses of bounce-back and of the ghost particles change U and Omega implicitly
// (exchange = "implicit", the default): each was computed with the colloid's velocity before
// it, and depends on it linearly, dP = dP_0 - G dX for a change dX = (dU, dOmega) (G: what
// the fluid's velocities would gain, as momentum and angular momentum about the centre, had
// the colloid moved faster by dX). The colloid takes the midpoint rule's change,
// (M + G/2) dX = dP, and the fluid that exchanged the impulse gets G dX/2 (the bounced
// particles 2 (dU + dOmega x s)/2 each, the particles of a cut cell the collision's response
// to a mean velocity shifted by the ghosts' dX/2): momentum and angular momentum stay
// conserved exactly, and a colloid in equilibrium keeps kT per degree of freedom, where the
// explicit change dX = M^-1 dP (exchange = "explicit") heats it by a factor ~1/(1 - G/2M) (an
// explicit Euler step of the friction).
//   hand_over              ghost colloids go; colloids that left the slab change owner (with
//                          the contact history they own)
// All calls are collective over the slabs' communicator.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/colloids/ghosts.hpp"
#include "narrows/colloids/hard_spheres.hpp"
#include "narrows/colloids/springs.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/mpcd/coupling/colloid_lookup.hpp"
#include "narrows/engines/mpcd/coupling/coupling.hpp"
#include "narrows/engines/mpcd/coupling/ghost_response.hpp"
#include "narrows/engines/mpcd/coupling/md_integrator.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace narrows::coupling {

struct NoSlipParams {
  double dt = 0.1, kT = 1.0, density = 10.0;
  std::uint64_t seed = 0;
  std::array<double, 3> gravity{0.0, 0.0, 0.0};     // acceleration of the colloids
  std::array<double, 3> fluid_accel{0.0, 0.0, 0.0}; // constant body force on the fluid
  double sine_amplitude = 0.0; // Kolmogorov force on the fluid, a_x = A sin(2 pi y / L_y)
  bool hard_contacts = false;
  bool spring_contacts = false; // springs with friction (then `spring` holds their constants)
  colloids::SpringParams spring;
  bool implicit = true; // the exchange of impulses (see above); false: explicit
};

// Turns colloid a's orientation by its angular velocity over time dt.
void rotate(colloids::Colloids &c, std::size_t a, double dt);

struct BounceStats {
  std::uint64_t particles = 0; // fluid particles bounced this step
  int deepest = 0;             // most halvings any one needed
};

class NoSlipCoupling final : public Coupling {
public:
  // The stop signal rides on the step's one collective: `received` gives this rank's (0 if
  // none), `agreed` takes the maximum over the ranks (the run loop's poll; set by the engine).
  struct StopSignalHooks {
    std::function<int()> received;
    std::function<void(int)> agreed;
  };
  void set_stop_signal_hooks(StopSignalHooks hooks) { stop_signal_ = std::move(hooks); }

  NoSlipCoupling(const NoSlipParams &params, const mpcd::Box &box, const parallel::Slabs &slabs);

  Stages before_stream(const StageContext &at) override;
  Stages after_stream(const StageContext &at) override;
  Stages after_bin(const StageContext &at) override;
  Stages within_collide(const StageContext &at) override;

  // fluid_v2_max: the largest |v|^2 of the fluid if known (the last collision found it), or
  // negative (a pass over the fluid finds it, on more than one rank).
  void move_colloids(const mpcd::Fluid &fluid, colloids::Colloids &c, double fluid_v2_max = -1.0);
  BounceStats bounce_back(mpcd::Fluid &fluid, colloids::Colloids &c, const FluidStream &stream);
  void add_ghost_particles(mpcd::CellGrid &grid, const colloids::Colloids &c, std::uint64_t step);
  // The cut cells' fluid gets its share of the implicit exchange by a pass over the fluid, or,
  // between MPC-AT+a's two passes (collision.shift_stride > 0), through the cells' records.
  void take_back_ghost_particles(mpcd::CellGrid &grid, mpcd::CollisionScratch &collision,
                                 mpcd::Fluid &fluid, colloids::Colloids &c);
  void hand_over(colloids::Colloids &c);
  // The colloids and the contact history they own to their owners under `slabs`; the ghost
  // colloids start afresh on them (collective, between steps).
  void set_slabs(const parallel::Slabs &slabs, colloids::Colloids &c) override;
  // Fluid particles this rank bounced back since the start (a count of the work balance).
  std::uint64_t bounced() const { return bounced_; }

  // Bytes this rank sent for colloids (ghosts, reverse sums, migration) since the start.
  std::uint64_t bytes_sent() const { return ghosts_.bytes_sent() + migration_.bytes_sent(); }
  // Seconds this rank spent in the calls above since the start (the ghost particles' share of
  // the collision itself is not included).
  double seconds() const { return seconds_; }
  // Of those, the seconds in colloid messages (ghost colloids, impulse sums, migration, the
  // reductions), waiting for the other ranks included: there the imbalance of the fluid's work
  // since the last message shows.
  double message_seconds() const { return message_seconds_; }
  // The same seconds by stage (messages and waiting included in each), for the profile line of
  // the log: names() and seconds in the same order.
  enum Stage {
    motion,
    contact_forces,
    lookup,
    bounce,
    ghost_sums,
    responses,
    solve,
    fluid_shift,
    hand_over_stage,
    stage_count
  };
  static const char *stage_name(int s);
  double stage_seconds(int s) const { return stage_seconds_[static_cast<std::size_t>(s)]; }
  // Hard-sphere collisions this rank resolved since the start (ghost rows included).
  const colloids::HardSphereStats &contacts() const { return contacts_; }
  // The spring contacts (nullptr unless contacts = "spring") and the contact history this rank
  // owns (the contacts of its colloids with larger ids and with the walls).
  const colloids::SpringContacts *springs() const { return springs_ ? &*springs_ : nullptr; }
  colloids::ContactHistory &contact_history() { return history_; }
  const colloids::ContactHistory &contact_history() const { return history_; }
  // Ghost particles added in the last step on this rank.
  std::size_t ghost_particles() const { return ghost_count_; }

private:
  // Spring contacts: moves the surface point s of colloid a (relative to its centre) out of the
  // colloids and walls a overlaps, onto the rim where the surfaces meet: 0 if it was outside
  // them, 1 if it moved, -1 if it could not (the rim inside a third).
  int leave_overlaps(const colloids::Colloids &c, std::size_t a, double *s) const;
  // Adds the impulse dp (on the colloid, at offset r from its centre) to row a's sums, and
  // the angular impulse `more` (1 or 3 components) if given.
  void add_impulse(std::size_t a, const double *r, const double *dp, const double *more = nullptr);
  // Sends the ghost rows' sums to their owners, which change U and Omega; zeroes the sums;
  // with `refresh` the ghosts get the new U and Omega. Implicit: the change solves
  // (M + G/2) dX = dP, every row (ghosts too, refreshed whatever `refresh` says) and half_
  // holds dX/2 for each row, the velocity change the fluid's share is computed for.
  void apply_impulses(colloids::Colloids &c, bool refresh);
  // Implicit exchange: adds to row a's G the response of a fluid correction whose velocity
  // change is J dX (J: dim x dof, row-major 3 x 6) summed over `count` particles whose mean
  // position is `lever` from the centre.
  void add_response(std::size_t a, const double (&J)[3][6], const double *lever);
  // Implicit exchange, ghost particles: each group's G (added to its row) and the fluid's
  // response per unit dX (ghost_particles.cpp); after the solve, the cut cells' fluid shifted.
  void ghost_responses(const mpcd::CellGrid &grid, const mpcd::CollisionScratch &collision,
                       const mpcd::Fluid &fluid);
  void planar_responses(const mpcd::CellGrid &grid, const mpcd::CollisionScratch &collision);
  void shift_cut_cells(const mpcd::CellGrid &grid, mpcd::CollisionScratch &collision,
                       mpcd::Fluid &fluid);
  void shift_cut_cells_fluid(const mpcd::CellGrid &grid, mpcd::Fluid &fluid);
  // Adds G (dof x dof) to row a's.
  void add_G(std::size_t a, const double (&G)[6][6]);
  // The velocity change J dX of a fluid particle at offset s from the centre, per unit of the
  // surface velocity's change dU + dOmega x s, times f.
  void surface_map(const double *s, double f, double (&J)[3][6]) const;

  NoSlipParams params_;
  mpcd::Box box_;
  int dim_;
  parallel::Slabs slabs_;
  colloids::ColloidGhosts ghosts_;
  parallel::Exchange migration_;
  ColloidLookup lookup_;
  std::vector<double> margin_;
  std::array<std::vector<double>, 3> start_; // owned colloid positions at the start of the step
  std::vector<std::uint8_t> trusted_;        // per row, for the hard contacts
  std::vector<std::size_t> active_, still_;  // bounce-back: batch rows still inside, per level
  mpcd::Fluid level_;                        // their copy while they fly
  std::vector<std::int64_t> impulse_; // per row: momentum (dim) and angular momentum (1 or 3),
                                      // implicit: then G (dof x dof, row-major)
  int dof_ = 3, stride_ = 3;
  std::vector<double> half_;   // implicit: per row, dX/2 of the last apply_impulses
  std::vector<double> before_; // scratch: U and Omega of each row before it
  // Implicit: the bounced particles' corrections (batch row, colloid row, surface point s, f:
  // 2, or 1 for a particle that takes the surface's velocity).
  struct Kick {
    std::size_t j, row;
    std::array<double, 3> s;
    double f;
  };
  std::vector<Kick> kicks_;
  // Implicit: per local cell the slot of a cut cell (-1: none); per slot the fluid particles'
  // count and summed in-cell offsets, and the velocity shift they get.
  std::vector<std::int32_t> cell_slot_;
  std::vector<std::array<double, 4>> slot_fluid_;
  std::vector<std::array<std::int64_t, 4>> slot_fixed_; // their fixed-point sums
  std::vector<std::array<std::int64_t, 9>> slot_sums_;  // per slot: du, dw, G dX/2's momentum
  std::vector<double> slot_total_; // particles in the cell's mean (ghosts, virtual ones too)
  std::vector<std::array<double, 3>> slot_rc_;
  std::vector<std::array<double, 6>> slot_motion_; // v += c + w x r: (c, w)
  // Implicit: per group and degree of freedom i of dX, the cell's mean velocity change (times
  // the rule's response) and rigid rotation it causes, and column i's momentum rows of G:
  // du (3), dw (3), G (dim) for each i in turn.
  std::vector<double> group_fluid_;
  std::vector<std::uint32_t> slot_cells_;
  // Bounce-back scratch: the particles being bounced, their fluid rows and colloid rows.
  mpcd::Fluid batch_;
  std::vector<std::size_t> batch_index_, candidates_;
  std::vector<std::int32_t> candidate_cells_; // the lookup cell of each candidate
  std::vector<long> batch_hit_;
  // Ghost particles of this step, one group per (colloid, cut cell) pair (grid.groups): the
  // colloid row, the cell's corner from the colloid's centre, the pair's key of draws.
  std::size_t ghost_count_ = 0;
  std::vector<std::uint32_t> group_row_;
  std::vector<std::array<double, 3>> group_corner_;
  std::vector<std::uint64_t> group_key_;
  struct CutCell {
    std::uint32_t row, cell;      // colloid row, local cell
    std::uint64_t key;            // the pair's key of draws (try 0)
    std::array<double, 3> corner; // the cell's corner from the colloid's centre
  };
  std::vector<CutCell> cut_;          // this step's cut cells first (its size: the most so far)
  std::vector<double> group_normals_; // the groups' Gaussian draws
  colloids::HardSphereStats contacts_;
  std::optional<colloids::SpringContacts> springs_;
  colloids::ContactHistory history_;
  StopSignalHooks stop_signal_;
  parallel::Exchange contact_migration_;
  std::vector<double> weight_; // M g of each owned colloid, a force in the spring sub-steps
  double seconds_ = 0.0;
  double message_seconds_ = 0.0;
  std::uint64_t bounced_ = 0;
  std::array<double, stage_count> stage_seconds_{};
};

} // namespace narrows::coupling
