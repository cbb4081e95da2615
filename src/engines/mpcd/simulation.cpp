// Building and stepping the MPCD pipeline.
#include "narrows/engines/mpcd/simulation.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"

#include "narrows/colloids/ownership.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"
#include "narrows/engines/mpcd/kernels/cell_sort.hpp"
#include "narrows/engines/mpcd/kernels/collision.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"
#include "narrows/engines/mpcd/kernels/thermostat.hpp"
#include "narrows/engines/mpcd/walls/bounce_back.hpp"
#include "narrows/engines/mpcd/walls/virtual_particles.hpp"
#include "narrows/parallel/message_clock.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/run/stop_signals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
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
    return fluid_count_with_colloids(*scene.colloids, make_box(scene), scene.fluid.density,
                                     scene.run.seed);
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

// How far (in cell columns) a fluid particle may go beyond its slab within one step: one column
// of grid shift, 12 thermal standard deviations of a velocity component times dt (a speed
// beyond has a probability of ~1e-33 per particle and step at equilibrium), the body force's
// push over the step, and 2 columns for mean flows. The fluid's exchange talks to the ranks
// within this reach only; a particle beyond it stops the run with a message.
double fluid_migration_columns(const MpcdPlan &p) {
  const double f =
      std::sqrt(p.force[0] * p.force[0] + p.force[1] * p.force[1] + p.force[2] * p.force[2]) +
      std::abs(p.sine_amplitude);
  return 3.0 + p.dt * 12.0 * std::sqrt(std::max(p.kT, 0.0)) + f * p.dt * p.dt;
}

} // namespace

std::size_t estimate_memory(const scene::Scene &scene) {
  return estimate_memory(scene, particle_count(scene));
}

std::size_t estimate_memory(const scene::Scene &scene, std::uint64_t particles) {
  return particles * bytes_per_particle(scene) +
         make_box(scene).num_cells() * bytes_per_cell(scene);
}

parallel::Slabs check_ranks(const scene::Scene &scene, MPI_Comm comm) {
  parallel::Slabs slabs(comm, make_box(scene).cells[0]);
  // Tabatabaei's random solvent (a) (Tabatabaei (2008) §4.3) interchanges the velocities of all
  // fluid particles; here they are permuted within the array of each rank, which on several ranks
  // would be another stream than on one (and not a permutation of all).
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
  if (plan_.slabs)
    exchange_.set_neighbours(slabs_, fluid_migration_columns(plan_), "fluid particle");
  if (plan_.no_slip) {
    coupling_ = &no_slip_.emplace(plan_.no_slip_params, box_, slabs_);
    no_slip_->set_stop_signal_hooks({run::stop_signal_received, run::hand_agreed_stop_signal});
  } else if (plan_.colloids)
    coupling_ = &md_.emplace(plan_.md, plan_.forces, box_, slabs_);
  build_stages();
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
        // A stop signal ends a long packing on every rank alike (it is the same everywhere).
        const auto poll = [comm] {
          int local = run::stop_signal_received(), any = 0;
          MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
          if (any != 0)
            throw Error(ExitCode::ok, std::string("received ") + run::signal_name(any) +
                                          " while packing the colloids: stopped before step 0, "
                                          "nothing written");
        };
        try {
          colloids_ = place_colloids(*scene.colloids, box_, scene.fluid.density, scene.run.seed,
                                     &report, poll);
        } catch (const Error &e) {
          if (e.code() != ExitCode::bad_input)
            throw;
          throw input_error(scene.file + ": " + e.what());
        }
        packing_ = report;
      } else {
        colloids_ = place_colloids(*scene.colloids, box_, scene.fluid.density, scene.run.seed);
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

void MpcdSimulation::migrate_to_owners(parallel::Reach reach) {
  // Used where nothing is binned (random solvent b), and for a checkpoint's blocks (reach
  // anywhere): one scan for particles outside the slab.
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
  exchange_.migrate(fluid_view(fluid_), strays_.index, stray_dest_, reach);
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

void MpcdSimulation::advance() {
  const double talked = parallel::message_seconds();
  const Stopwatch watch;
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
    if (ranks > 1) // only this rank knows: the others wait in the step's next message (one
                   // line even when several ranks fail in the same step)
      run::abort_with_line(comm_, what, static_cast<int>(ExitCode::invariant));
    throw invariant_error(what);
  }
  window_busy_ += watch.seconds() - (parallel::message_seconds() - talked);
  ++step_;
  count_work();
}

void MpcdSimulation::count_work() {
  WorkCounts w;
  w.fluid = static_cast<double>(fluid_.size());
  w.colloids = static_cast<double>(colloids_.size()); // owned: the ghosts left
  if (no_slip_) {
    w.bounces = static_cast<double>(no_slip_->bounced() - bounced_);
    bounced_ = no_slip_->bounced();
    w.ghosts = static_cast<double>(no_slip_->ghost_particles());
    if (const auto *springs = no_slip_->springs()) {
      w.contacts = static_cast<double>(springs->contact_updates() - contact_updates_);
      contact_updates_ = springs->contact_updates();
    }
  }
  work_ += w;
  window_ += w;
  const std::int64_t every = scene_.domain.balance_every;
  if (every <= 0 || step_ % every != 0 || slabs_.ranks() == 1)
    return;
  // One small collective every `every` steps: the window's work and busy time of every rank.
  const double mine[2] = {window_.work(), window_busy_};
  const auto ranks = static_cast<std::size_t>(slabs_.ranks());
  std::vector<double> both(2 * ranks), all(ranks), busy(ranks);
  MPI_Allgather(mine, 2, MPI_DOUBLE, both.data(), 2, MPI_DOUBLE, comm_);
  for (std::size_t r = 0; r < ranks; ++r) {
    all[r] = both[2 * r];
    busy[r] = both[2 * r + 1];
  }
  window_ = WorkCounts{};
  window_busy_ = 0.0;
  // The same arithmetic on the same numbers: every rank decides alike.
  const double ratio = imbalance(all), busy_ratio = imbalance(busy);
  const double threshold = scene_.domain.balance_threshold;
  bool moved = false;
  if (scene_.domain.balance == scene::Balance::work && ratio > threshold)
    moved = balance_work(&all, static_cast<double>(every));
  else if (scene_.domain.balance == scene::Balance::time && busy_ratio > threshold)
    moved = balance_work(&all, static_cast<double>(every), speed_shares(all, busy));
  balance_checks_.push_back({step_, ratio, busy_ratio, moved});
}

bool MpcdSimulation::balance_work(const std::vector<double> *window_work, double window_steps,
                                  const std::vector<double> &shares) {
  if (slabs_.ranks() == 1)
    return false;
  using W = WorkWeights;
  const int columns = box_.cells[0];
  // Per column the estimated work of a step; then the run's counts so far (over all ranks) for
  // the mean bounce-backs, ghost particles and contact updates per colloid, and the contacts
  // held now.
  std::vector<double> local(static_cast<std::size_t>(columns) + 5, 0.0);
  for (std::size_t i = 0; i < fluid_.size(); ++i)
    local[static_cast<std::size_t>(mpcd::cell_coordinate(fluid_.x[0][i], 0.0, columns))] +=
        W::fluid;
  const colloids::ContactHistory *history = no_slip_ ? &no_slip_->contact_history() : nullptr;
  const double substeps =
      no_slip_ && no_slip_->springs() ? plan_.no_slip_params.spring.substeps : 0.0;
  double *totals = &local[static_cast<std::size_t>(columns)];
  totals[0] = work_.colloids;
  totals[1] = work_.bounces;
  totals[2] = work_.ghosts;
  totals[3] = work_.contacts;
  totals[4] = history ? static_cast<double>(history->size()) : 0.0;
  std::vector<double> all(slabs_.rank() == 0 ? local.size() : 0);
  MPI_Reduce(local.data(), all.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM, 0,
             comm_);
  // The colloids' columns and the contacts' (at their owner colloid), on rank 0.
  std::vector<int> mine_cols;
  for (std::size_t a = 0; a < colloids_.size(); ++a)
    mine_cols.push_back(mpcd::cell_coordinate(colloids_.x[0][a], 0.0, columns));
  const std::size_t colloid_count = mine_cols.size();
  if (history)
    for (std::size_t j = 0; j < history->size(); ++j) {
      const auto it = std::lower_bound(colloids_.id.begin(), colloids_.id.end(), history->owner[j]);
      if (it != colloids_.id.end() && *it == history->owner[j])
        mine_cols.push_back(mine_cols[static_cast<std::size_t>(it - colloids_.id.begin())]);
    }
  // Tagged: colloids as column, contacts as -1 - column.
  for (std::size_t j = colloid_count; j < mine_cols.size(); ++j)
    mine_cols[j] = -1 - mine_cols[j];
  const int count = static_cast<int>(mine_cols.size());
  std::vector<int> counts(static_cast<std::size_t>(slabs_.ranks())), displs(counts.size());
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::vector<int> cols;
  if (slabs_.rank() == 0) {
    int n = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      displs[r] = n;
      n += counts[r];
    }
    cols.resize(static_cast<std::size_t>(n));
  }
  MPI_Gatherv(mine_cols.data(), count, MPI_INT, cols.data(), counts.data(), displs.data(), MPI_INT,
              0, comm_);
  std::vector<int> first(static_cast<std::size_t>(slabs_.ranks()));
  if (slabs_.rank() == 0) {
    const double *t = &all[static_cast<std::size_t>(columns)];
    const bool counted = t[0] > 0.0;
    // (the defaults are the no-slip coupling's; MD colloids have neither)
    const double bounces = counted ? t[1] / t[0] : no_slip_ ? W::bounces_per_colloid : 0.0;
    const double ghosts = counted ? t[2] / t[0] : no_slip_ ? W::ghosts_per_colloid : 0.0;
    double per_colloid = W::colloid + W::bounce * bounces + W::ghost * ghosts;
    // Contacts where they are; before any is held (the start), a mean share per colloid.
    if (substeps > 0.0 && t[4] == 0.0)
      per_colloid += W::contact * (counted ? t[3] / t[0] : W::contact_updates_per_colloid);
    std::vector<double> work(all.begin(), all.begin() + columns);
    for (int c : cols) {
      if (c >= 0)
        work[static_cast<std::size_t>(c)] += per_colloid;
      else
        work[static_cast<std::size_t>(-1 - c)] += W::contact * substeps;
    }
    // What each rank counted corrects the estimate of its columns (the per-colloid means miss
    // where the bounce-backs and ghost particles are).
    if (window_work && window_steps > 0.0)
      for (int r = 0; r < slabs_.ranks(); ++r) {
        const int lo = slabs_.first_column_of(r);
        const int hi = r + 1 < slabs_.ranks() ? slabs_.first_column_of(r + 1) : columns;
        double estimate = 0.0;
        for (int c = lo; c < hi; ++c)
          estimate += work[static_cast<std::size_t>(c)];
        const double counted = (*window_work)[static_cast<std::size_t>(r)] / window_steps;
        if (estimate > 0.0 && counted > 0.0)
          for (int c = lo; c < hi; ++c)
            work[static_cast<std::size_t>(c)] *= counted / estimate;
      }
    first = balanced_first_columns(work, slabs_.ranks(), 1, shares);
  }
  MPI_Bcast(first.data(), static_cast<int>(first.size()), MPI_INT, 0, comm_);
  if (first == slabs_.first_columns())
    return false;
  set_slabs(first);
  return true;
}

void MpcdSimulation::set_slabs(const std::vector<int> &first_columns) {
  const std::array<double, 3> shift = grid_.shift;
  slabs_ = parallel::Slabs(comm_, box_.cells[0], first_columns);
  grid_ = mpcd::CellGrid(box_, slabs_.first_column(), slabs_.local_columns());
  grid_.shift = shift; // the fluid lies in the slabs of the last step's shifted columns
  migrate_to_owners(parallel::Reach::anywhere); // (the old slabs' neighbours may not reach)
  exchange_.set_neighbours(slabs_, fluid_migration_columns(plan_), "fluid particle");
  restored_ = false;
  coupling_->set_slabs(slabs_, colloids_);
}

coupling::FluidStream MpcdSimulation::stream_kernel() const {
  // The exact kernel for what the scene has, chosen once: the fluid's stage and the colloid
  // couplings (MD sub-steps, bounce-back intervals) stream with it.
  const MpcdPlan &p = plan_;
  switch (p.stream) {
  case MpcdPlan::Stream::free:
    return [this](mpcd::Fluid &f, double t) { mpcd::stream_free(f, box_, t); };
  case MpcdPlan::Stream::constant_force:
    return
        [this](mpcd::Fluid &f, double t) { mpcd::stream_constant_force(f, box_, t, plan_.force); };
  case MpcdPlan::Stream::sine_force:
    return [this](mpcd::Fluid &f, double t) {
      mpcd::stream_sine_force(f, box_, t, plan_.sine_amplitude);
    };
  case MpcdPlan::Stream::channel:
    return [this](mpcd::Fluid &f, double t) {
      walls::stream_channel(f, box_, t, plan_.force, plan_.slip);
    };
  }
  throw std::logic_error("MpcdSimulation: no streaming kernel for the plan");
}

// The step as a list of stages, in the order they run, each with its line of the pipeline. Only
// what the scene has becomes a stage; the coupling adds its own at its four hooks.
void MpcdSimulation::build_stages() {
  const MpcdPlan &p = plan_;
  const coupling::StageContext at{fluid_,
                                  colloids_,
                                  grid_,
                                  collision_scratch_,
                                  stream_kernel(),
                                  stream_text(scene_, p, box_),
                                  colloids_text(scene_, p)};
  std::vector<Stage> &list = stages_;
  list.clear();
  const auto add = [&list](coupling::Stages more) {
    for (Stage &stage : more)
      list.push_back(std::move(stage));
  };
  add(coupling_->before_stream(at));
  // Every particle, the whole step (walls, body force exact).
  list.push_back(
      {at.stream_name, [this, stream = at.stream](std::uint64_t) { stream(fluid_, plan_.dt); }});
  add(coupling_->after_stream(at));
  list.push_back({"grid shift", [this](std::uint64_t step) { // the same on every rank
                    grid_.set_shift(mpcd::grid_shift(plan_.seed, step, plan_.dim));
                  }});
  const std::string ranks = std::to_string(p.ranks);
  if (p.collision == scene::Collision::random_maxwell) { // random solvent (b): no cells
    if (!coupling_->after_bin(at).empty() || !coupling_->within_collide(at).empty())
      throw std::logic_error("MpcdSimulation: a coupling with cell stages and no cells");
    if (p.slabs)
      list.push_back({"migrate to slab owners (" + ranks + " ranks)",
                      [this](std::uint64_t) { migrate_to_owners(); }});
    list.push_back(
        {"draw Maxwell-Boltzmann velocities (random solvent)", [this](std::uint64_t step) {
           mpcd::draw_maxwell_velocities(fluid_, plan_.kT, plan_.seed, step);
         }});
    return;
  }
  if (p.slabs) {
    // Binning also lists the particles whose shifted column left this slab (a thin band at
    // each edge); they go to their owners, where they are binned on arrival.
    list.push_back({"bin into cells, list particles leaving the slab",
                    [this](std::uint64_t) { mpcd::bin_particles(fluid_, grid_, &strays_); }});
    list.push_back({"migrate to slab owners (" + ranks + " ranks), bin arrivals",
                    [this](std::uint64_t) { migrate_strays_and_bin_arrivals(); }});
  } else {
    list.push_back(
        {"bin into cells", [this](std::uint64_t) { mpcd::bin_particles(fluid_, grid_); }});
  }
  add(coupling_->after_bin(at));
  if (p.virtual_particles) // fill the cells cut by the walls to the mean density
    list.push_back({std::string("virtual particles in cells cut by the walls (") +
                        (p.virtual_mirror ? "mirror-image flow)" : "at rest)"),
                    [this](std::uint64_t step) {
                      walls::add_virtual_particles(grid_, plan_.density, plan_.kT, plan_.seed, step,
                                                   plan_.virtual_at_noise, plan_.virtual_mirror);
                    }});
  const std::string kT = format_number(p.kT);
  switch (p.collision) { // each resets v2_max first: only MPC-AT+a finds it
  case scene::Collision::srd:
  case scene::Collision::random_permute: // SRD, then the velocities are permuted
    list.push_back({"collide SRD (angle " + format_number(scene_.fluid.angle_deg) + " deg)",
                    [this](std::uint64_t step) {
                      collision_scratch_.v2_max = -1.0;
                      mpcd::collide_srd(fluid_, grid_, collision_scratch_, plan_.angle_rad,
                                        plan_.seed, step);
                    }});
    break;
  case scene::Collision::at:
    list.push_back({"collide MPC-AT (kT " + kT + ")", [this](std::uint64_t step) {
                      collision_scratch_.v2_max = -1.0;
                      mpcd::collide_at(fluid_, grid_, collision_scratch_, plan_.kT, plan_.seed,
                                       step);
                    }});
    break;
  case scene::Collision::at_a: { // in two passes: the coupling's change to the cells between
    coupling::Stages within = coupling_->within_collide(at);
    list.push_back({"collide MPC-AT+a (kT " + kT + ", angular momentum): the cells",
                    [this, room = !within.empty()](std::uint64_t step) {
                      collision_scratch_.v2_max = -1.0;
                      mpcd::collide_at_a_cells(fluid_, grid_, collision_scratch_, plan_.kT,
                                               plan_.seed, step, room);
                    }});
    add(std::move(within));
    list.push_back({"collide MPC-AT+a: the particles' new velocities", [this](std::uint64_t) {
                      mpcd::collide_at_a_particles(fluid_, grid_, collision_scratch_);
                    }});
    break;
  }
  case scene::Collision::random_maxwell: // no cells: above
    break;
  }
  if (p.collision == scene::Collision::random_permute) // one rank only (check_ranks)
    list.push_back({"permute all velocities (random solvent)", [this](std::uint64_t step) {
                      mpcd::permute_velocities(fluid_, collision_scratch_, plan_.seed, step);
                    }});
  if (p.collision != scene::Collision::at_a) // (after the whole collision)
    add(coupling_->within_collide(at));
  // The thermostats change the velocities after the collision, so its v2_max no longer holds.
  if (p.thermostat == MpcdPlan::Thermostat::layers)
    list.push_back({"thermostat: rescale velocities relative to the cell means per layer of "
                    "cells to kT " +
                        kT + " (Tabatabaei (2008) eq 3.53-3.54)",
                    [this](std::uint64_t) {
                      mpcd::rescale_layers(fluid_, grid_, plan_.kT, layer_sums_, comm_);
                      collision_scratch_.v2_max = -1.0;
                    }});
  if (p.thermostat == MpcdPlan::Thermostat::monte_carlo)
    list.push_back({"thermostat: Monte Carlo scaling of each cell's relative velocities toward "
                    "kT " +
                        kT + ", gamma " + format_number(p.gamma) +
                        " (Tabatabaei (2008) eq 3.55-3.57)",
                    [this](std::uint64_t step) {
                      mpcd::monte_carlo_cells(fluid_, grid_, plan_.kT, plan_.gamma, plan_.seed,
                                              step, layer_sums_);
                      collision_scratch_.v2_max = -1.0;
                    }});
  if (p.sort_every > 0) // locality: counting sort by cell
    list.push_back({"sort by cell (every " + std::to_string(p.sort_every) + " steps)",
                    [this](std::uint64_t step) {
                      if ((step + 1) % plan_.sort_every == 0)
                        mpcd::sort_by_cell(fluid_, grid_, sort_scratch_);
                    }});
}

std::vector<std::string> describe_pipeline(const std::vector<Stage> &stages) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < stages.size(); ++i)
    lines.push_back("  " + std::to_string(i + 1) + ". " + stages[i].name);
  return lines;
}

// One MPCD step: the stages of the list, in order.
void MpcdSimulation::step_stages() {
  const auto step = static_cast<std::uint64_t>(step_);
  if (restored_) { // a checkpoint's blocks: each particle to the slab of its unshifted column,
    // (as after binning: colloid ghosts assume the fluid near its slab)
    migrate_to_owners(parallel::Reach::anywhere);
    restored_ = false;
  }
  for (const Stage &stage : stages_)
    stage.run(step);
}

} // namespace narrows::mpcd
