// Checks of a restarted MPCD state, which io/ (a leaf without physics) does not make: the
// checkpoint's stored scene against its data, the fluid field by field, and the fluid against
// the colloids.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <string>

namespace narrows::mpcd {

// Refuses (input_error naming `path`) a checkpoint whose data were not made with its stored
// scene: /parameters/seed other than its run.seed, or box edges other than its domain.size. A
// stored scene that does not parse is left to the restart's comparison of the scenes.
void check_stored_scene(const io::CheckpointInfo &info, const std::string &path);

// Refuses (collectively, one line naming the dataset and the first bad row over all ranks) a
// fluid just read from `path` (this rank's block of the rows, io::read_species) that a run cannot
// continue: an id outside [0, total) or twice, a position outside the box edges of `info`, a
// non-finite velocity.
void check_restored_fluid(const mpcd::Fluid &fluid, const io::CheckpointInfo &info,
                          std::uint64_t total, const std::string &path, MPI_Comm comm);

// Refuses (input_error, collectively: every rank ends with the same one line, exit 2) a
// restarted fluid with a particle inside a colloid where no running simulation can have put
// it: its WCA pair force (Tabatabaei (2008) eq 3.42, sigma = the colloid's radius, strength
// `epsilon`) has a component beyond the fixed-point range (fixed::max_magnitude), at which the
// force loop of a run stops with exit 3 (colloids/pair_geometry.hpp, to_fixed). The line names
// `file`, /particles/fluid/position/value, the fluid id (the smallest such id on any rank), the
// colloid id, the distance and the pair energy in units of `kT`.
//
// `local_fluid`: this rank's fluid; `all_colloids`: every colloid (on every rank). Fluid and
// colloids are binned by the largest cut-off, so the cost is O(N + Nc) for colloids that do not
// overlap.
void check_fluid_outside_colloids(const mpcd::Fluid &local_fluid,
                                  const colloids::Colloids &all_colloids, const mpcd::Box &box,
                                  double epsilon, double kT, const std::string &file,
                                  MPI_Comm comm);

// Refuses (input_error naming `path`, the dataset, the row and what is allowed) restored colloids
// (all of them, on every rank, so every rank refuses alike) in a state no run of `scene` can
// reach (issue 35 item 1):
// - the colloids' box edges other than the scene's domain.size, a centre outside the box or in
//   a wall (with [walls]: 0 < y < L_y);
// - a speed |v_k| or a surface speed |omega_k| r above the run's speed limit (max_speed);
// - two colloids overlapping beyond the contact model's allowance: hard contacts none (the event
//   loop's rounding margin 1e-6 (1 + L_x)); spring contacts a centre inside the other colloid;
//   MD colloids a 48-24 pair force (Tabatabaei (2008) eq 3.43) beyond the fixed-point range, at
//   which a run stops; hard contacts likewise off the walls, MD colloids a wall force beyond it;
// - spring contacts: a contact row between colloids that do not touch (or a wall contact of a
//   colloid off the wall), a tangential spring beyond its Coulomb cap, and after step 0 (whose
//   history is empty: the first force evaluation makes it) a touching pair (colloid or wall)
//   without its contact row (rows removed, or the contact group deleted).
void check_restored_colloids(const colloids::Colloids &all,
                             const colloids::ContactHistory &contacts, const scene::Scene &scene,
                             const std::array<double, 3> &edges, std::int64_t step,
                             const std::string &path);

} // namespace narrows::mpcd
