// The validated scene: plain structs filled from a TOML file by scene/parse.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace narrows::scene {

enum class Engine { mpcd, lgca, kmc, continuum };
enum class Collision { srd, at, at_a, random_permute, random_maxwell };
enum class ForceKind { constant, sine };

struct Run {
  Engine engine = Engine::mpcd;
  int dimensions = 2;      // 2 | 3
  std::uint64_t seed = 42; // key of every random draw
  std::int64_t steps = 0;  // the step at which the run ends
};

struct Domain {
  std::array<double, 3> size{0.0, 0.0, 0.0}; // whole cells along x, y[, z]; z unused in 2D
};

struct Fluid {
  Collision collision = Collision::srd;
  double density = 10.0;   // mean particles per cell
  double dt = 0.1;         // collision time step
  double angle_deg = 90.0; // SRD rotation angle
  double kT = 1.0;
  int sort_every = 20; // counting sort by cell every this many steps (0 = never)
};

// Force per unit mass on every fluid particle.
struct BodyForce {
  ForceKind kind = ForceKind::constant;
  std::array<double, 3> value{0.0, 0.0, 0.0}; // constant: the acceleration vector
  double amplitude = 0.0; // sine: a_x = amplitude * sin(2 pi y / L_y) (Kolmogorov flow)
};

struct Output {
  std::string dir = "out";
  std::int64_t every = 100; // observables cadence in steps
  std::vector<std::string> observables{"temperature", "momentum", "velocity_profile",
                                       "density_profile"};
  std::int64_t checkpoint_every = 0; // 0 = only at the end of the run
  int checkpoint_keep = 2;           // newest checkpoints kept in the output directory
  bool progress = true;              // progress line with ETA on long runs
};

struct Scene {
  std::string file; // where it came from, for messages
  std::string text; // the scene as read (stored in output files)
  Run run;
  Domain domain;
  Fluid fluid;
  std::optional<BodyForce> body_force;
  Output output;
};

// Names used in messages and files.
const char *to_string(Engine e);
const char *to_string(Collision c);

} // namespace narrows::scene
