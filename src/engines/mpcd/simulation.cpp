// Building and stepping the MPCD pipeline.
#include "narrows/engines/mpcd/simulation.hpp"

#include "narrows/core/error.hpp"

#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/engines/mpcd/kernels/cell_sort.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"
#include "narrows/engines/mpcd/kernels/thermostat.hpp"
#include "narrows/engines/mpcd/walls/bounce_back.hpp"
#include "narrows/engines/mpcd/walls/virtual_particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace narrows::mpcd {

mpcd::Box make_box(const scene::Scene &scene) {
  std::array<int, 3> cells{1, 1, 1};
  for (int k = 0; k < scene.run.dimensions; ++k)
    cells[k] = static_cast<int>(std::lround(scene.domain.size[k]));
  mpcd::Box box = mpcd::make_periodic_box(scene.run.dimensions, cells);
  box.walls_y = scene.walls.has_value();
  return box;
}

std::uint64_t particle_count(const scene::Scene &scene) {
  if (scene.colloids)
    return colloids::fluid_count_with_colloids(*scene.colloids, make_box(scene),
                                               scene.fluid.density, scene.run.seed);
  return mpcd::fluid_particle_count(make_box(scene), scene.fluid.density);
}

parallel::SoaView fluid_view(mpcd::Fluid &f) { return parallel::view(table(f), species::migrates); }

namespace {

// Bytes per particle: positions, velocities, id, cell; the AT rules add their noise arrays,
// the sort its buffers (one array of each type).
std::size_t bytes_per_particle(const scene::Scene &s) {
  const std::size_t d = s.run.dimensions;
  std::size_t b = 2 * d * 8 + 8 + 4;
  const auto rule = s.fluid.collision;
  if (rule == scene::Collision::at || rule == scene::Collision::at_a)
    b += d * 8;
  if (s.fluid.sort_every > 0)
    b += 8 + 8 + 4 + 4;
  if (s.colloids) // MD: fixed-point force, flags, cell-list link (near copies not counted)
    b += d * 8 + 1 + 1 + 4;
  return b;
}

std::size_t bytes_per_cell(const scene::Scene &s) {
  const std::size_t d = s.run.dimensions;
  std::size_t b = sizeof(mpcd::CellSums) + (d == 2 ? 4 : 12) * 8;
  if (s.fluid.collision == scene::Collision::at_a)
    b += (d == 2 ? 9 : 18) * 8;
  if (s.fluid.sort_every > 0)
    b += 4;
  return b;
}

} // namespace

std::size_t estimate_memory(const scene::Scene &scene) {
  return particle_count(scene) * bytes_per_particle(scene) +
         make_box(scene).num_cells() * bytes_per_cell(scene);
}

parallel::Slabs check_ranks(const scene::Scene &scene, MPI_Comm comm) {
  parallel::Slabs slabs(comm, make_box(scene).cells[0]);
  // The seed's random solvent (a) interchanges the velocities of all fluid particles; here
  // they are permuted within the array of each rank, which on several ranks would be another
  // stream than on one (and not a permutation of all).
  if (scene.fluid.collision == scene::Collision::random_permute && slabs.ranks() > 1)
    throw input_error((scene.file.empty() ? "" : scene.file + ": ") +
                      "fluid.collision = \"random-permute\" permutes the velocities of all "
                      "particles only on one rank; found " +
                      std::to_string(slabs.ranks()) +
                      " ranks; allowed: 1 rank, or fluid.collision = \"random-maxwell\" (the "
                      "other random solvent, the same on any number of ranks)");
  return slabs;
}

MpcdSimulation::MpcdSimulation(const scene::Scene &scene, MPI_Comm comm, bool allocate)
    : scene_(scene), comm_(comm), box_(make_box(scene)), slabs_(check_ranks(scene, comm)),
      exchange_(comm), plan_(make_plan(scene, box_, slabs_.ranks())) {
  for (auto &line : describe_pipeline(scene, plan_, box_))
    stages_.push_back({std::move(line)});
  if (plan_.no_slip)
    no_slip_.emplace(plan_.no_slip_params, box_, slabs_);
  else if (plan_.colloids)
    md_.emplace(plan_.md, plan_.forces, box_, slabs_);
  if (allocate) {
    grid_ = mpcd::CellGrid(box_, slabs_.first_column(), slabs_.local_columns());
    // Each rank keeps the particles (drawn per id) of its own cells, so nothing migrates at
    // the start and the state is the same on any number of ranks.
    const std::uint64_t total = particle_count(scene);
    if (scene.colloids) {
      if (scene.colloids->placement == scene::ColloidPlacement::packing) {
        // Packed here only (run_scene leaves it out of check_colloid_placement): every rank
        // packs the same colloids; a target that cannot be packed is the scene's error.
        colloids::PackingReport report;
        try {
          colloids_ = colloids::place_colloids(*scene.colloids, box_, scene.fluid.density,
                                               scene.run.seed, &report);
        } catch (const Error &e) {
          if (e.code() != ExitCode::bad_input)
            throw;
          throw input_error(scene.file + ": " + e.what());
        }
        packing_ = report;
      } else {
        colloids_ =
            colloids::place_colloids(*scene.colloids, box_, scene.fluid.density, scene.run.seed);
      }
      const colloids::ColloidCover cover(colloids_, box_);
      const mpcd::Exclusion exclusion{
          [&](const std::array<double, 3> &p) { return cover.inside(p); }};
      mpcd::init_fluid(fluid_, box_, scene.fluid.kT, scene.run.seed, total, slabs_.first_column(),
                       slabs_.local_columns(), comm, &exclusion);
      colloids::keep_owned(colloids_, slabs_); // every rank placed all; each keeps its own
    } else {
      mpcd::init_fluid(fluid_, box_, scene.fluid.kT, scene.run.seed, total, slabs_.first_column(),
                       slabs_.local_columns(), comm);
    }
  }
}

void MpcdSimulation::restore(mpcd::Fluid &&fluid, std::int64_t step) {
  grid_ = mpcd::CellGrid(box_, slabs_.first_column(), slabs_.local_columns());
  fluid_ = std::move(fluid);
  step_ = step;
  restored_ = plan_.slabs; // the next step first sends each particle to its slab (collective)
}

void MpcdSimulation::restore_colloids(colloids::Colloids &&all) {
  colloids_ = std::move(all);
  colloids::keep_owned(colloids_, slabs_);
}

colloids::Colloids MpcdSimulation::gather_colloids() const {
  return colloids::gather_colloids(colloids_, comm_);
}

colloids::ContactHistory MpcdSimulation::gather_contacts() const {
  if (!no_slip_) {
    colloids::ContactHistory none;
    none.dim = box_.dim;
    return none;
  }
  return colloids::gather_contacts(no_slip_->contact_history(), comm_);
}

void MpcdSimulation::restore_contacts(colloids::ContactHistory &&all) {
  if (!no_slip_)
    return;
  colloids::keep_contacts_of(all, colloids_);
  no_slip_->contact_history() = std::move(all);
}

std::uint64_t MpcdSimulation::colloid_bytes_sent() const {
  return md_ ? md_->bytes_sent() : no_slip_ ? no_slip_->bytes_sent() : 0;
}

void MpcdSimulation::migrate_to_owners() {
  // Used where nothing is binned (random solvent b): one scan for particles outside the slab.
  const std::size_t n = fluid_.size();
  const double sx = grid_.shift[0];
  const int columns = box_.cells[0], first = slabs_.first_column();
  const auto width = static_cast<unsigned>(slabs_.local_columns());
  strays_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const int column = mpcd::cell_coordinate(fluid_.x[0][i], sx, columns);
    if (static_cast<unsigned>(column - first) >= width) {
      strays_.index.push_back(i);
      strays_.column.push_back(column);
    }
  }
  stray_dest_.resize(strays_.column.size());
  for (std::size_t j = 0; j < stray_dest_.size(); ++j)
    stray_dest_[j] = slabs_.owner(strays_.column[j]);
  exchange_.migrate(fluid_view(fluid_), strays_.index, stray_dest_);
}

void MpcdSimulation::migrate_strays_and_bin_arrivals() {
  // Binning listed the particles whose shifted column left this slab (a thin band at each
  // edge); they go to their owners, and what arrives is added to the cell sums.
  stray_dest_.resize(strays_.column.size());
  for (std::size_t j = 0; j < stray_dest_.size(); ++j)
    stray_dest_[j] = slabs_.owner(strays_.column[j]);
  const std::size_t staying = fluid_.size() - strays_.index.size();
  exchange_.migrate(fluid_view(fluid_), strays_.index, stray_dest_);
  mpcd::bin_more_particles(fluid_, grid_, staying);
}

void MpcdSimulation::stream(mpcd::Fluid &fluid, double t) const {
  const MpcdPlan &p = plan_;
  switch (p.stream) {
  case MpcdPlan::Stream::free:
    mpcd::stream_free(fluid, box_, t);
    break;
  case MpcdPlan::Stream::constant_force:
    mpcd::stream_constant_force(fluid, box_, t, p.force);
    break;
  case MpcdPlan::Stream::sine_force:
    mpcd::stream_sine_force(fluid, box_, t, p.sine_amplitude);
    break;
  case MpcdPlan::Stream::channel:
    walls::stream_channel(fluid, box_, t, p.force, p.slip);
    break;
  }
}

void MpcdSimulation::bin_into_cells() {
  // With slabs, binning also lists the particles whose shifted column left this slab (a thin
  // band at each edge); they go to their owners, where they are binned on arrival.
  if (plan_.slabs) {
    mpcd::bin_particles(fluid_, grid_, &strays_);
    migrate_strays_and_bin_arrivals();
  } else {
    mpcd::bin_particles(fluid_, grid_);
  }
}

void MpcdSimulation::collide(std::uint64_t step) {
  const MpcdPlan &p = plan_;
  collision_scratch_.v2_max = -1.0; // only MPC-AT+a finds it
  switch (p.collision) {
  case scene::Collision::srd:
  case scene::Collision::random_permute: // SRD, then the velocities are permuted
    mpcd::collide_srd(fluid_, grid_, collision_scratch_, p.angle_rad, p.seed, step);
    break;
  case scene::Collision::at:
    mpcd::collide_at(fluid_, grid_, collision_scratch_, p.kT, p.seed, step);
    break;
  case scene::Collision::at_a:
    mpcd::collide_at_a(fluid_, grid_, collision_scratch_, p.kT, p.seed, step);
    break;
  case scene::Collision::random_maxwell: // no cells: see advance()
    break;
  }
  if (p.collision == scene::Collision::random_permute)
    mpcd::permute_velocities(fluid_, collision_scratch_, p.seed, step);
}

void MpcdSimulation::thermostat(std::uint64_t step) {
  const MpcdPlan &p = plan_;
  switch (p.thermostat) {
  case MpcdPlan::Thermostat::none:
    return;
  case MpcdPlan::Thermostat::layers: // seed 000 eq 3.53-3.54
    mpcd::rescale_layers(fluid_, grid_, p.kT, layer_sums_, comm_);
    break;
  case MpcdPlan::Thermostat::monte_carlo: // seed 000 eq 3.55-3.57
    mpcd::monte_carlo_cells(fluid_, grid_, p.kT, p.gamma, p.seed, step, layer_sums_);
    break;
  }
  collision_scratch_.v2_max = -1.0; // the velocities changed after the collision
}

void MpcdSimulation::advance() {
  try {
    step_stages();
  } catch (const Error &e) { // a kernel named the particle; the step and rank are added here
    if (e.code() != ExitCode::invariant || std::string_view(e.what()).starts_with("invariant"))
      throw;
    int rank = 0, ranks = 1;
    MPI_Comm_rank(comm_, &rank);
    MPI_Comm_size(comm_, &ranks);
    const std::string what = "invariant broken at step " + std::to_string(step_) + " on rank " +
                             std::to_string(rank) + ": " + e.what();
    if (ranks > 1) { // only this rank knows: the others wait in the step's next message
      std::fprintf(stderr, "narrows: %s\n", what.c_str());
      std::fflush(stderr);
      MPI_Abort(comm_, static_cast<int>(ExitCode::invariant));
    }
    throw invariant_error(what);
  }
  ++step_;
}

// One MPCD step. Every stage is a call; the plan (built once from the scene) says which.
void MpcdSimulation::step_stages() {
  const MpcdPlan &p = plan_;
  const auto step = static_cast<std::uint64_t>(step_);
  if (restored_) { // a checkpoint's blocks: each particle to the slab of its unshifted column,
    migrate_to_owners(); // as after binning (colloid ghosts assume the fluid near its slab)
    restored_ = false;
  }
  const auto streamer = [this](mpcd::Fluid &f, double t) { stream(f, t); };
  if (p.no_slip) // ghost colloids; gravity; every colloid moves (with hard contacts if any)
    no_slip_->move_colloids(fluid_, colloids_, collision_scratch_.v2_max);
  else if (p.colloids) // forces now; ghost colloids; copies out the fluid that may meet a colloid
    md_->take_near_fluid(fluid_, colloids_);
  stream(fluid_, p.dt); // every particle, the whole step (walls, body force exact)
  if (p.no_slip) {      // fluid that entered a colloid goes back out, the colloids recoil
    no_slip_->bounce_back(fluid_, colloids_, streamer);
  } else if (p.colloids) { // MD sub-steps of the colloids and those copies, which then go back
    md_->substeps(colloids_, streamer);
    md_->put_back_near_fluid(fluid_);
    md_->check_paths(colloids_);
    md_->hand_over(colloids_); // ghosts dropped; colloids that left the slab change owner
  }
  grid_.set_shift(mpcd::grid_shift(p.seed, step, p.dim)); // the same on every rank
  if (p.collision == scene::Collision::random_maxwell) {  // random solvent (b): no cells
    if (p.slabs)
      migrate_to_owners();
    mpcd::draw_maxwell_velocities(fluid_, p.kT, p.seed, step);
  } else {
    bin_into_cells(); // with slabs: particles leaving the slab migrate, arrivals are binned
    if (p.no_slip)    // ghost particles fill the cells the colloids cut
      no_slip_->add_ghost_particles(grid_, colloids_, step);
    if (p.virtual_particles) // fill the cells cut by the walls to the mean density
      walls::add_virtual_particles(grid_, p.density, p.kT, p.seed, step, p.virtual_at_noise,
                                   p.virtual_mirror);
    collide(step);
    if (p.no_slip) { // their momentum change to the colloids; ghosts leave, colloids may too
      no_slip_->take_back_ghost_particles(grid_, collision_scratch_, colloids_);
      no_slip_->hand_over(colloids_);
    }
    thermostat(step);
    if (p.sort_every > 0 && (step + 1) % p.sort_every == 0) // locality: counting sort by cell
      mpcd::sort_by_cell(fluid_, grid_, sort_scratch_);
  }
}

} // namespace narrows::mpcd
