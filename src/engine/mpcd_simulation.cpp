// Building and stepping the MPCD pipeline.
#include "narrows/engine/mpcd_simulation.hpp"

#include "narrows/core/error.hpp"

#include "narrows/colloids/placement.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/mpcd/streaming.hpp"
#include "narrows/mpcd/thermostat.hpp"
#include "narrows/walls/bounce_back.hpp"
#include "narrows/walls/virtual_particles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string_view>

namespace narrows::engine {

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

parallel::SoaView fluid_view(mpcd::Fluid &f) {
  parallel::SoaView v;
  for (int k = 0; k < f.dim; ++k)
    v.reals.push_back(&f.x[k]);
  for (int k = 0; k < f.dim; ++k)
    v.reals.push_back(&f.v[k]);
  v.words.push_back(&f.id);
  v.halfwords.push_back(&f.cell);
  return v;
}

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

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

} // namespace

std::size_t estimate_memory(const scene::Scene &scene) {
  return particle_count(scene) * bytes_per_particle(scene) +
         make_box(scene).num_cells() * bytes_per_cell(scene);
}

MpcdSimulation::MpcdSimulation(const scene::Scene &scene, MPI_Comm comm, bool allocate)
    : scene_(scene), comm_(comm), box_(make_box(scene)), slabs_(comm, box_.cells[0]),
      exchange_(comm) {
  if (allocate) {
    grid_ = mpcd::CellGrid(box_, slabs_.first_column(), slabs_.local_columns());
    // Ids in contiguous blocks per rank; the first migration sends each to its owner.
    const std::uint64_t total = particle_count(scene);
    const auto r = static_cast<std::uint64_t>(slabs_.rank());
    const auto p = static_cast<std::uint64_t>(slabs_.ranks());
    const std::uint64_t first = total * r / p, last = total * (r + 1) / p;
    mpcd::Excluded excluded;
    if (scene.colloids) {
      colloids_ =
          colloids::place_colloids(*scene.colloids, box_, scene.fluid.density, scene.run.seed);
      excluded = [this](const std::array<double, 3> &p) {
        return colloids::inside_any(colloids_, box_, p);
      };
    }
    mpcd::init_fluid(fluid_, box_, scene.fluid.kT, scene.run.seed, first, last - first, total, comm,
                     excluded);
  }
  build_pipeline();
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

void MpcdSimulation::build_pipeline() {
  const auto &f = scene_.fluid;
  const std::uint64_t seed = scene_.run.seed;
  const double dt = f.dt;
  const int dim = box_.dim;
  const auto rule = f.collision;

  // 1. Stream, exactly for the body force the scene has (and the walls); with colloids the
  // same drift runs between the velocity-Verlet kicks of every MD sub-step.
  std::string name;
  colloids::FluidDrift drift;
  const mpcd::Box box = box_;
  if (scene_.walls) {
    const bool slip = scene_.walls->slip;
    const std::array<double, 3> g =
        scene_.body_force ? scene_.body_force->value : std::array<double, 3>{0.0, 0.0, 0.0};
    name = std::string("stream with ") + (slip ? "slip (specular)" : "no-slip bounce-back") +
           " walls at y = 0 and y = " + format_number(box_.length[1]);
    if (scene_.body_force) {
      name += ", constant force [";
      for (int k = 0; k < dim; ++k)
        name += format_number(g[k]) + (k + 1 < dim ? ", " : "], exact hit times");
    }
    drift = [box, g, slip](mpcd::Fluid &fl, double t) {
      walls::stream_channel(fl, box, t, g, slip);
    };
  } else if (!scene_.body_force) {
    name = "stream (free flight)";
    drift = [box](mpcd::Fluid &fl, double t) { mpcd::stream_free(fl, box, t); };
  } else if (scene_.body_force->kind == scene::ForceKind::constant) {
    const auto g = scene_.body_force->value;
    name = "stream (constant force [";
    for (int k = 0; k < dim; ++k)
      name += format_number(g[k]) + (k + 1 < dim ? ", " : "])");
    drift = [box, g](mpcd::Fluid &fl, double t) { mpcd::stream_constant_force(fl, box, t, g); };
  } else {
    const double A = scene_.body_force->amplitude;
    name = "stream (sine force a_x = " + format_number(A) + " sin(2 pi y/L_y), exact)";
    drift = [box, A](mpcd::Fluid &fl, double t) { mpcd::stream_sine_force(fl, box, t, A); };
  }
  if (scene_.colloids) {
    const auto &c = *scene_.colloids;
    colloids::MdParams p;
    p.substeps = c.md_substeps;
    p.tau = dt / c.md_substeps;
    p.epsilon = c.epsilon;
    p.sigma_wall = c.wall_sigma; // 0: 2 r_a for each colloid
    p.wall_q = c.wall_q;
    p.gravity = c.gravity;
    if (scene_.body_force) {
      const auto &b = *scene_.body_force;
      p.fluid_accel = b.kind == scene::ForceKind::sine
                          ? std::abs(b.amplitude)
                          : std::sqrt(b.value[0] * b.value[0] + b.value[1] * b.value[1] +
                                      b.value[2] * b.value[2]);
    }
    md_.emplace(p, box_, drift);
    // Sizes from the scene (on a restart the colloids are not here yet): the radii are drawn
    // from (seed, id) alone.
    std::string size =
        "r " + format_number(c.radius) + ", M " + format_number(c.effective_mass(dim, f.density));
    double r_lo = c.radius, r_hi = c.radius;
    if (c.radius_sd > 0.0) {
      for (std::int64_t i = 0; i < c.count; ++i) {
        const double r = colloids::colloid_radius(c, seed, static_cast<std::uint64_t>(i));
        r_lo = std::min(r_lo, r);
        r_hi = std::max(r_hi, r);
      }
      size = "r " + format_number(c.radius) + " sd " + format_number(c.radius_sd) +
             " truncated at 3 sd, drawn " + format_number(r_lo) + " to " + format_number(r_hi);
      if (c.mass > 0.0)
        size += ", M " + format_number(c.mass);
      else
        size += ", M " + format_number(c.mass_of(dim, f.density, r_lo)) + " to " +
                format_number(c.mass_of(dim, f.density, r_hi));
    }
    std::string md = "MD: " + std::to_string(c.count) + " colloids (" + size + "), " +
                     std::to_string(c.md_substeps) + " velocity-Verlet sub-steps of " +
                     format_number(p.tau) + ": WCA colloid-fluid, 48-24 colloid-colloid";
    if (scene_.walls) {
      const double lo = c.wall_sigma_of(r_lo), hi = c.wall_sigma_of(r_hi);
      if (lo == hi)
        md += ", LJ wall (sigma_w " + format_number(lo) + ", cut-off " +
              format_number(colloids::wall_cutoff(lo)) + ")";
      else
        md += ", LJ wall (sigma_w 2 r_a " + format_number(lo) + " to " + format_number(hi) +
              ", cut-off " + format_number(colloids::wall_cutoff(lo)) + " to " +
              format_number(colloids::wall_cutoff(hi)) + ")";
    }
    if (c.gravity != std::array<double, 3>{0.0, 0.0, 0.0})
      md += ", gravity";
    stages_.push_back({md + "; fluid between kicks: " + name,
                       [this](std::uint64_t) { md_->advance(fluid_, colloids_, comm_); }});
  } else {
    stages_.push_back({name, [this, dt, drift](std::uint64_t) { drift(fluid_, dt); }});
  }

  // 2. Shifted grid: the same on every rank without a message.
  stages_.push_back({"grid shift", [this, seed, dim](std::uint64_t step) {
                       grid_.set_shift(mpcd::grid_shift(seed, step, dim));
                     }});
  const bool slabs = slabs_.ranks() > 1;
  const std::string ranks = std::to_string(slabs_.ranks());

  // 3. Random solvent (b) needs no cells at all; with slabs, particles still go to the rank
  // that owns their column.
  if (rule == scene::Collision::random_maxwell) {
    if (slabs)
      stages_.push_back({"migrate to slab owners (" + ranks + " ranks)",
                         [this](std::uint64_t) { migrate_to_owners(); }});
    const double kT = f.kT;
    stages_.push_back({"draw Maxwell-Boltzmann velocities (random solvent)",
                       [this, kT, seed](std::uint64_t step) {
                         mpcd::draw_maxwell_velocities(fluid_, kT, seed, step);
                       }});
    return;
  }
  // Binning; with slabs it also lists the particles that left the slab, which then migrate
  // to the ranks owning their columns, where they are binned on arrival.
  if (slabs) {
    stages_.push_back({"bin into cells, list particles leaving the slab",
                       [this](std::uint64_t) { mpcd::bin_particles(fluid_, grid_, &strays_); }});
    stages_.push_back({"migrate to slab owners (" + ranks + " ranks), bin arrivals",
                       [this](std::uint64_t) { migrate_strays_and_bin_arrivals(); }});
  } else {
    stages_.push_back(
        {"bin into cells", [this](std::uint64_t) { mpcd::bin_particles(fluid_, grid_); }});
  }

  // Virtual particles fill the cells cut by the walls to the mean density.
  if (scene_.walls && scene_.walls->virtual_particles) {
    const double density = f.density, kT = f.kT;
    const bool at_noise = rule == scene::Collision::at || rule == scene::Collision::at_a;
    const bool mirror = scene_.walls->virtual_flow == scene::VirtualFlow::mirror;
    stages_.push_back({std::string("virtual particles in cells cut by the walls (") +
                           (mirror ? "mirror-image flow)" : "at rest)"),
                       [this, density, kT, seed, at_noise, mirror](std::uint64_t step) {
                         walls::add_virtual_particles(grid_, density, kT, seed, step, at_noise,
                                                      mirror);
                       }});
  }

  // 4. Collision.
  const double angle = f.angle_deg * std::numbers::pi / 180.0;
  const double kT = f.kT;
  switch (rule) {
  case scene::Collision::srd:
  case scene::Collision::random_permute:
    stages_.push_back({"collide SRD (angle " + format_number(f.angle_deg) + " deg)",
                       [this, angle, seed](std::uint64_t step) {
                         mpcd::collide_srd(fluid_, grid_, collision_scratch_, angle, seed, step);
                       }});
    break;
  case scene::Collision::at:
    stages_.push_back(
        {"collide MPC-AT (kT " + format_number(kT) + ")", [this, kT, seed](std::uint64_t step) {
           mpcd::collide_at(fluid_, grid_, collision_scratch_, kT, seed, step);
         }});
    break;
  case scene::Collision::at_a:
    stages_.push_back({"collide MPC-AT+a (kT " + format_number(kT) + ", angular momentum)",
                       [this, kT, seed](std::uint64_t step) {
                         mpcd::collide_at_a(fluid_, grid_, collision_scratch_, kT, seed, step);
                       }});
    break;
  case scene::Collision::random_maxwell:
    break;
  }
  if (rule == scene::Collision::random_permute)
    stages_.push_back({slabs_.ranks() > 1 ? "permute velocities within each rank (random solvent)"
                                          : "permute all velocities (random solvent)",
                       [this, seed](std::uint64_t step) {
                         mpcd::permute_velocities(fluid_, collision_scratch_, seed, step);
                       }});

  // Thermostat: per-layer rescaling relative to the cell means (seed 000 eq 3.53-3.54).
  if (scene_.thermostat && scene_.thermostat->kind == scene::ThermostatKind::layers)
    stages_.push_back({"thermostat: rescale velocities relative to the cell means per layer of "
                       "cells to kT " +
                           format_number(kT) + " (seed 000 eq 3.53-3.54)",
                       [this, kT](std::uint64_t) {
                         mpcd::rescale_layers(fluid_, grid_, kT, layer_sums_, comm_);
                       }});
  if (scene_.thermostat && scene_.thermostat->kind == scene::ThermostatKind::monte_carlo) {
    const double gamma = scene_.thermostat->gamma;
    stages_.push_back({"thermostat: Monte Carlo scaling of each cell's relative velocities "
                       "toward kT " +
                           format_number(kT) + ", gamma " + format_number(gamma) +
                           " (seed 000 eq 3.55-3.57)",
                       [this, kT, gamma, seed](std::uint64_t step) {
                         mpcd::monte_carlo_cells(fluid_, grid_, kT, gamma, seed, step, layer_sums_);
                       }});
  }

  // 5. Locality: counting sort by cell on a schedule.
  if (f.sort_every > 0) {
    const std::uint64_t every = static_cast<std::uint64_t>(f.sort_every);
    stages_.push_back({"sort by cell (every " + std::to_string(every) + " steps)",
                       [this, every](std::uint64_t step) {
                         if ((step + 1) % every == 0)
                           mpcd::sort_by_cell(fluid_, grid_, sort_scratch_);
                       }});
  }
}

void MpcdSimulation::advance() {
  const auto s = static_cast<std::uint64_t>(step_);
  try {
    for (const Stage &stage : stages_)
      stage.run(s);
  } catch (const Error &e) { // a kernel names the particle; the step and rank are added here
    if (e.code() != ExitCode::invariant || std::string_view(e.what()).starts_with("invariant"))
      throw;
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    throw invariant_error("invariant broken at step " + std::to_string(step_) + " on rank " +
                          std::to_string(rank) + ": " + e.what());
  }
  ++step_;
}

} // namespace narrows::engine
