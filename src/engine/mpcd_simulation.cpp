// Building and stepping the MPCD pipeline.
#include "narrows/engine/mpcd_simulation.hpp"

#include "narrows/mpcd/streaming.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace narrows::engine {

mpcd::Box make_box(const scene::Scene &scene) {
  std::array<int, 3> cells{1, 1, 1};
  for (int k = 0; k < scene.run.dimensions; ++k)
    cells[k] = static_cast<int>(std::lround(scene.domain.size[k]));
  return mpcd::make_periodic_box(scene.run.dimensions, cells);
}

std::uint64_t particle_count(const scene::Scene &scene) {
  const mpcd::Box box = make_box(scene);
  double volume = 1.0;
  for (int k = 0; k < box.dim; ++k)
    volume *= box.length[k];
  return static_cast<std::uint64_t>(std::llround(scene.fluid.density * volume));
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
    : scene_(scene), comm_(comm), box_(make_box(scene)) {
  if (allocate) {
    grid_ = mpcd::CellGrid(box_);
    mpcd::init_fluid(fluid_, box_, scene.fluid.density, scene.fluid.kT, scene.run.seed);
  }
  build_pipeline();
}

void MpcdSimulation::build_pipeline() {
  const auto &f = scene_.fluid;
  const std::uint64_t seed = scene_.run.seed;
  const double dt = f.dt;
  const int dim = box_.dim;
  const auto rule = f.collision;

  // 1. Stream, exactly for the body force the scene has.
  if (!scene_.body_force) {
    stages_.push_back({"stream (free flight)",
                       [this, dt](std::uint64_t) { mpcd::stream_free(fluid_, box_, dt); }});
  } else if (scene_.body_force->kind == scene::ForceKind::constant) {
    const auto g = scene_.body_force->value;
    std::string name = "stream (constant force [";
    for (int k = 0; k < dim; ++k)
      name += format_number(g[k]) + (k + 1 < dim ? ", " : "])");
    stages_.push_back(
        {name, [this, dt, g](std::uint64_t) { mpcd::stream_constant_force(fluid_, box_, dt, g); }});
  } else {
    const double A = scene_.body_force->amplitude;
    stages_.push_back(
        {"stream (sine force a_x = " + format_number(A) + " sin(2 pi y/L_y), exact)",
         [this, dt, A](std::uint64_t) { mpcd::stream_sine_force(fluid_, box_, dt, A); }});
  }

  // 2. Random solvent (b) needs no cells at all.
  if (rule == scene::Collision::random_maxwell) {
    const double kT = f.kT;
    stages_.push_back({"draw Maxwell-Boltzmann velocities (random solvent)",
                       [this, kT, seed](std::uint64_t step) {
                         mpcd::draw_maxwell_velocities(fluid_, kT, seed, step);
                       }});
    return;
  }

  // 3. Shifted grid and binning.
  stages_.push_back({"grid shift + bin into cells", [this, seed, dim](std::uint64_t step) {
                       grid_.shift = mpcd::grid_shift(seed, step, dim);
                       mpcd::bin_particles(fluid_, grid_);
                     }});

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
    stages_.push_back({"permute all velocities (random solvent)", [this, seed](std::uint64_t step) {
                         mpcd::permute_velocities(fluid_, collision_scratch_, seed, step);
                       }});

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
  for (const Stage &stage : stages_)
    stage.run(s);
  ++step_;
}

} // namespace narrows::engine
