// The MPCD plan: the scene's choices resolved once into plain fields the step's stage list is
// built from (which streaming kernel, colloids or not, slabs or not, which collision rule,
// thermostat, sorting), and the words for the stages whose text only the scene knows.
#pragma once

#include "narrows/colloids/forces.hpp"
#include "narrows/engines/mpcd/coupling/md_integrator.hpp"
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace narrows::mpcd {

struct MpcdPlan {
  int dim = 2;
  std::uint64_t seed = 0;
  double dt = 0.1, kT = 1.0;

  // Streaming: the exact kernel for the body force the scene has, or the channel kernel with
  // walls (constant force `force`, slip or bounce-back).
  enum class Stream { free, constant_force, sine_force, channel };
  Stream stream = Stream::free;
  std::array<double, 3> force{0.0, 0.0, 0.0};
  double sine_amplitude = 0.0;
  bool slip = false;

  // Colloids: MD sub-steps within each step, or (no_slip) bounce-back and ghost particles.
  bool colloids = false;
  bool no_slip = false;
  coupling::NoSlipParams no_slip_params;
  coupling::MdParams md;
  colloids::ForceParams forces;

  // More than one rank: particles migrate to the rank owning their (shifted) cell column.
  bool slabs = false;
  int ranks = 1;

  scene::Collision collision = scene::Collision::srd;
  double angle_rad = 0.0; // SRD rotation angle
  bool virtual_particles = false, virtual_mirror = false, virtual_at_noise = false;
  double density = 10.0;

  enum class Thermostat { none, layers, monte_carlo };
  Thermostat thermostat = Thermostat::none;
  double gamma = 0.0;

  std::uint64_t sort_every = 0; // 0: never
};

MpcdPlan make_plan(const scene::Scene &scene, const mpcd::Box &box, int ranks);

// The words of the pipeline for what only the scene knows; the step's stage list
// (MpcdSimulation::build_stages) names its stages with them.
// A number as the pipeline prints it (as %g).
std::string format_number(double v);
// The streaming stage: free flight, body force, walls.
std::string stream_text(const scene::Scene &scene, const MpcdPlan &plan, const mpcd::Box &box);
// The colloids: count, sizes and masses, and their forces (MD) or how they move (no-slip);
// empty without [colloids].
std::string colloids_text(const scene::Scene &scene, const MpcdPlan &plan);

} // namespace narrows::mpcd
