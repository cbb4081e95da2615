// The validated scene: plain structs filled from a TOML file by scene/parse.
#pragma once

#include "narrows/models/three_state/model.hpp"

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

// How the MPCD box's slabs along x are chosen: equal numbers of cell columns, or boundaries that
// even the counted work of the ranks (at the start, on a restart, and every balance_every steps
// when the work's max/mean over the ranks exceeds balance_threshold), or (time) that even the
// ranks' measured busy time: each rank's share of the counted work in proportion to the work it
// did per busy second over the last balance_every steps (cores of unequal speed, work the
// counts miss). Results are the same.
enum class Balance { none, work, time };

struct Domain {
  std::array<double, 3> size{0.0, 0.0, 0.0}; // whole cells along x, y[, z]; z unused in 2D
  Balance balance = Balance::none;
  std::int64_t balance_every = 0; // steps between checks of the imbalance (0: start only)
  double balance_threshold = 1.05;
};

struct Fluid {
  Collision collision = Collision::srd;
  double density = 10.0;   // mean particles per cell
  double dt = 0.1;         // collision time step
  double angle_deg = 90.0; // SRD rotation angle
  double kT = 1.0;
  int sort_every = 20; // counting sort by cell every this many steps (0 = never)
};

// What the body force drives: the fluid alone (Kanehl (thesis) §5.1: "a constant force acting on
// each fluid particle"), or the fluid and the colloids, as a pressure gradient does: it pushes a
// colloid of volume V with sigma V = M a for a neutrally buoyant colloid (M = rho V).
enum class DriveTarget { fluid, fluid_and_colloids };

// Force per unit mass on every fluid particle (and, with acts_on = fluid_and_colloids, on every
// colloid: M value).
struct BodyForce {
  ForceKind kind = ForceKind::constant;
  std::array<double, 3> value{0.0, 0.0, 0.0}; // constant: the acceleration vector
  double amplitude = 0.0; // sine: a_x = amplitude * sin(2 pi y / L_y) (Kolmogorov flow)
  DriveTarget acts_on = DriveTarget::fluid;
};

// Mean velocity of the virtual wall particles: at rest with the wall (Tabatabaei (2008) eq 3.14),
// or the mirror image of the flow next to the wall (its antisymmetric continuation, no-slip walls).
enum class VirtualFlow { rest, mirror };

// Planar walls at y = 0 and y = L_y (2D channel; 3D slit with periodic z).
struct Walls {
  bool slip = false; // specular reflection instead of no-slip bounce-back
  // Fill cells cut by a wall to the mean density (Tabatabaei (2008) eq 3.14).
  bool virtual_particles = true;
  VirtualFlow virtual_flow = VirtualFlow::rest;
};

// MD-coupled colloids of Tabatabaei (2008) §3.4 (species "colloids"). Radii: `radius`, or with
// radius_sd > 0 each drawn from a Gaussian of that mean and standard deviation truncated at
// +-3 sd (engines/mpcd/colloid_placement.hpp). Potentials, with each colloid's own radius r_a:
// colloid-fluid WCA (sigma_cf = r_a), colloid-colloid 48-24 (sigma_cc = r_a + r_b, 2 r_c for
// equal radii), integrated LJ wall (with [walls]); gravity is the gravitational field g_c of
// Tabatabaei (2008) (an acceleration: the force on a colloid is its mass times g, eq 4.4 without
// buoyancy, as the fluid feels no gravity).
//
// packing: grown from points with frictionless springs and no fluid to colloids.packing_fraction
// (Kanehl (thesis) §6.1, colloids/packing.hpp); the counts follow from that fraction.
enum class ColloidPlacement { lattice, list, random, packing };
// How colloids meet the fluid: "md" (Tabatabaei (2008) §3.4: WCA forces, velocity-Verlet sub-steps,
// slip) or "no-slip" (Kanehl (thesis) §4.2.1: bounce-back at the surface with the rigid-body
// velocity, ghost particles inside in the collision; colloids rotate). Contacts between colloids
// and with the walls: "none", "hard" (event-driven rough hard spheres, Kanehl (thesis) §4.2.2) or
// "spring" (linear springs with Coulomb friction and contact history, Kanehl (thesis) §4.2.3;
// [colloids.spring]).
enum class ColloidCoupling { md, no_slip };
enum class ColloidContacts { none, hard, spring };

// [colloids.spring]: the constants of the spring contacts (Kanehl (thesis) Table 6.1: kn = kt =
// 2500; §6.2.1: mu = 1). mu = infinity ("inf"): never slides. No damping: the thesis has none.
struct ColloidSprings {
  double kn = 2500.0, kt = 2500.0;
  double mu_cc = 1.0, mu_cw = 1.0;
  int substeps = 10; // velocity-Verlet sub-steps per MPCD step
};

// One kind of colloid of a [[colloids.kind]] table: `count` colloids of one radius and mass
// (mass 0: fluid mass density times the volume).
struct ColloidKind {
  double radius = 2.0;
  double mass = 0.0;
  std::int64_t count = 0;
};

struct Colloids {
  double radius = 2.0;
  double radius_sd = 0.0; // standard deviation of the radii (0: all equal to radius)
  double mass = 0.0;      // 0: pi r^2 n (2D) or (4/3) pi r^3 n (3D), n = fluid.density
  std::int64_t count = 0;
  ColloidPlacement placement = ColloidPlacement::lattice; // lattice: a row along x, centred
  ColloidCoupling coupling = ColloidCoupling::md;
  ColloidContacts contacts = ColloidContacts::none;
  bool exchange_implicit = true; // no-slip impulses: the midpoint rule (false: explicit)
  ColloidSprings spring;         // contacts = "spring"
  std::vector<std::array<double, 3>> positions; // placement "list"
  double packing_fraction = 0.0;                // placement "packing": the target fraction
  // placement "packing": the largest estimated work (colloids::packing_work, colloid-steps)
  double packing_max_work = 1e9;
  // Where each position was given, for messages: "colloids.positions[3]" or
  // "colloids.positions_file (path:line)"; empty: "colloids.positions[i]".
  std::vector<std::string> position_keys;
  std::array<double, 3> gravity{0.0, 0.0, 0.0}; // acceleration g; force M g
  int md_substeps = 15;                         // tau_MD = fluid.dt / md_substeps
  double epsilon = 1.0;                         // eps_cf = eps_cc = eps_w (kT units)
  double wall_sigma = 0.0; // sigma_w of the wall potential, 0: 2 r_a (Tabatabaei (2008) table 3.1)
  double wall_q = 1.0;     // q of eq 3.35
  // Several kinds ([[colloids.kind]]; empty: the one kind of radius, radius_sd, mass, count).
  // Ids are given kind by kind: kind 0 has ids 0..count_0-1, kind 1 the next count_1, ...;
  // `count` is then the total, `radius` the largest radius.
  std::vector<ColloidKind> kinds;
  // Colloid statistics (observables colloid_vacf, colloid_diffusion, colloid_msd,
  // colloid_angular_vacf, density_kde): velocities sampled every correlation_every steps,
  // lags 0..max_lag steps, kernel width kde_width, time averages from step statistics_from.
  std::int64_t max_lag = 1000;
  std::int64_t correlation_every = 1;
  double kde_width = 0.25;
  std::int64_t statistics_from = 0;

  // The largest radius a colloid can have: radius + 3 radius_sd (the truncation), or the
  // largest radius of the kinds.
  double max_radius() const;
  // The number of kinds (1 without [[colloids.kind]]) and the kind of colloid `id`.
  std::size_t kind_count() const { return kinds.empty() ? 1 : kinds.size(); }
  std::size_t kind_of(std::uint64_t id) const;
  // The mass of a colloid of radius r: `mass` if set, else fluid mass density times its volume.
  double mass_of(int dim, double density, double r) const;
  // The mass of colloid `id` of radius r: its kind's mass if set (kinds), else mass_of.
  double mass_of_id(int dim, double density, std::uint64_t id, double r) const;
  double effective_mass(int dim, double density) const { return mass_of(dim, density, radius); }
  // sigma_w of a colloid of radius r: `wall_sigma` if set, else 2 r.
  double wall_sigma_of(double r) const { return wall_sigma > 0.0 ? wall_sigma : 2.0 * r; }
  double effective_wall_sigma() const { return wall_sigma_of(radius); }
};

// Thermostats of Tabatabaei (2008) §3.4: "layers" rescales velocities relative to the cell means
// per layer of cells across the channel (eq 3.53-3.54) to fluid.kT after every collision.
// "monte-carlo" scales each cell's relative velocities by a random factor accepted with the
// Boltzmann weight (eq 3.55-3.57), step size `gamma`.
enum class ThermostatKind { layers, monte_carlo };

struct Thermostat {
  ThermostatKind kind = ThermostatKind::layers;
  double gamma = 0.1; // monte-carlo: eps uniform in [0, gamma]
};

struct Output {
  std::string dir = "out";
  std::int64_t every = 100; // observables cadence in steps
  // parse_scene sets the engine's defaults (scene/schema.hpp) unless the scene lists them
  std::vector<std::string> observables;
  std::int64_t checkpoint_every = 0; // 0 = only at the end of the run
  int checkpoint_keep = 2;           // newest checkpoints kept in the output directory
  bool progress = true;              // progress line with ETA on long runs
  std::int64_t trajectory_every =
      0; // fluid frames to trajectory.h5 every this many steps (0 = none)
  std::int64_t trajectory_subsample = 1; // frames hold the particles whose id is a multiple of this
  double axial_bin = 2.0; // width of the bins along x of the mpcd observable axial_fields
  // Windows of the colloid profiles (mpcd density_kde, evolution, colloid_velocity_profile) in
  // steps from colloids.statistics_from; 0: one average over the whole run.
  std::int64_t kde_window = 0;
};

// Engine "kmc": the three-state lattice gas of Tabatabaei (2008) ch.2
// (models/three_state/model.hpp).
using KmcBoundary = three_state::Boundary;
using KmcPreset = three_state::Preset;
using KmcInitial = three_state::Initial;
using Kmc = three_state::Model;

// Engine "lgca": FHP lattice gases on the triangular lattice and the 1D d'Humieres model (seed
// 002; docs/scenes.md). Lattice units: spacing 1, step 1.
enum class LgcaModel { fhp_i, fhp_ii, fhp_iii, fhp_saturated, dhumieres_1d };
// zero_momentum (1D model): exactly N = round(L b d) particles and total momentum 0, the
// {N, P = 0} ensemble of van der Hoef & Frenkel §3.4.
enum class LgcaInitial { equilibrium, shear_wave, zero_momentum };

// A solid disc of sites (bounce-back) at (x, y) in lattice coordinates (row y at y sqrt(3)/2).
struct LgcaObstacle {
  double x = 0.0, y = 0.0, radius = 0.0;
};

struct Lgca {
  LgcaModel model = LgcaModel::fhp_i;
  std::vector<std::int64_t> size; // sites along x, y (2D; size[1] even) or [L] (1D)
  double density = 0.0;           // mean occupation per link d
  LgcaInitial initial = LgcaInitial::equilibrium;
  double amplitude = 0.0;  // shear wave: u_x = amplitude sin(2 pi y / L_y)
  bool walls = false;      // solid rows y = 0 and y = size[1] - 1 (no-slip bounce-back)
  double body_force = 0.0; // probability per site and step of moving a particle from -x to +x
  std::vector<LgcaObstacle> obstacles;
  std::int64_t block = 0; // side of the square blocks of the density/velocity fields
};

// Tagged-particle VACF by moment propagation (optional section [tagged]).
struct Tagged {
  std::int64_t max_lag = 100;
  std::int64_t replicas = 1; // 1D model: independent runs (spread over the ranks)
};

// A colloidal disc with the Ladd-Frenkel rules, held in place or moving (optional section
// [colloid], FHP models; held = false not with walls or obstacles).
struct LgcaColloid {
  double x = 0.0, y = 0.0; // initial centre, Cartesian (row y of sites is at y sqrt(3)/2)
  double radius = 2.5, mass = 680.0;
  double vx = 0.0, vy = 0.0;
  bool held = true;
  std::int64_t max_lag = 1000;           // VACF of the colloid velocity, lags 0..max_lag
  std::int64_t displacement_lag = 5000;  // virtual displacement D(t) up to this lag
  std::int64_t displacement_every = 100; // ... at lags that are multiples of this
};

// Engine "continuum", model "conservation-law": rho_t + J(rho)_x = D rho_xx in 1D by finite
// volumes (continuum/). The lattice-gas fluxes are those of the kmc presets (kmc/preset.hpp):
// `lattice_gas` holds their rates (tasep and family2: preset family2, tasep with c = 0).
// Model "jamming": phi_t + (phi v)_x = D phi_xx, v_t + v v_x = sigma - xi(phi) v (Kanehl (thesis)
// eq 6.2-6.6, xi = sigma / v_ss with v_ss fitted in Table 6.2), periodic, pseudo-spectral. Model
// "segregation": the area (volume) fractions phi_i(y, t) of one or two colloid kinds across a
// channel y in [-w, w] in Poiseuille flow (Kanehl (thesis) eq 5.13-5.30), finite volumes, RK4.
enum class ContinuumModel { conservation_law, jamming, segregation };
enum class JammingFit { mu_infinity, mu_1, mu_half, mu_0 }; // the columns of Table 6.2
// Where the jamming model's v_ss parameters (eq 6.4) come from: a column of Table 6.2
// (continuum.mu), the scene itself (continuum.vss) or a fit file (continuum.vss_fit).
enum class JammingVss { preset, given, file };
enum class ContinuumFlux { burgers, tasep, family1, family2, colloid_chain };
enum class ContinuumBoundary { open, periodic };
enum class ContinuumInitial { riemann, profile, sine, cells, random, eigenmode };
enum class ContinuumLimiter { mc, minmod };
enum class SegregationShear { poiseuille, viscous };

// One colloid kind of the segregation model ([[continuum.kind]]).
struct SegregationKind {
  double radius = 0.0;      // a_i
  double fraction = 0.0;    // mean area (volume) fraction phi_i over the channel
  double diffusivity = 0.0; // single-colloid D_0^i
};

// The segregation model's parameters (Kanehl (thesis) ch.5); the channel is [-half_width,
// half_width].
struct Segregation {
  int dimensions = 2; // d of eq 5.13 and the structure factor (5.19-5.20 or 5.21-5.22)
  double half_width = 0.0;
  double centre_speed = 0.0; // v0: shear rate 2 v0 |y| / w^2 of the uniform suspension
  SegregationShear shear = SegregationShear::poiseuille;
  double k_c = 1.0, k_eta = 1.51, k_d = 7.46; // K_c, K_eta, K_d (eq 5.3, 5.23)
  double max_packing = 0.82;                  // phi_M of eq 5.29
  std::vector<SegregationKind> kinds;
};

struct Continuum {
  ContinuumModel model = ContinuumModel::conservation_law;
  ContinuumFlux flux = ContinuumFlux::burgers;
  Kmc lattice_gas;                            // tasep, family1, family2: rates and preset
  double c = 5.71, c_prime = 0.019, v_cm = 0; // colloid-chain: J = rho (c rho + c' - v_cm)
  double length = 0.0;                        // domain [0, length]
  std::int64_t cells = 0;
  double diffusion = 0.0; // D
  ContinuumBoundary boundary = ContinuumBoundary::open;
  std::array<double, 2> reservoirs{}; // open: densities held left of 0 and right of length
  ContinuumInitial initial = ContinuumInitial::riemann;
  double left = 0.0, right = 0.0, position = 0.0; // riemann: left | right at position
  std::vector<double> profile; // profile: values at equally spaced points; cells: cell averages
  double mean = 0.0, amplitude = 0.0; // sine: mean + amplitude sin(2 pi x / length)
  double time = 0.0;                  // simulated time
  std::int64_t samples = 100;         // observable samples over `time` (+ t = 0)
  double cfl = 0.4;                   // Courant number of the time step
  double max_work = 1e11;             // refuse more grid-point steps (about 3 h)
  ContinuumLimiter limiter = ContinuumLimiter::mc;
  // jamming only
  JammingFit fit = JammingFit::mu_1; // v_ss of Table 6.2 for this wall friction
  JammingVss vss_source = JammingVss::preset;
  // given or file: delta_v, delta_phi, phi_c, e1, e2, phi_q of eq 6.4 (and the file's errors of
  // each, NaN when it gives none); vss_file as written in the scene and resolved.
  std::array<double, 6> vss{}, vss_error{};
  std::string vss_file, vss_path;
  double drive = 1.0;              // sigma of eq 6.3
  std::int64_t mode = 1;           // sine: mean + amplitude sin(2 pi mode x / length)
  std::uint64_t seed = 1;          // random: mean + amplitude * uniform(-1, 1) per point
  std::vector<std::int64_t> modes; // eigenmode: the modes n excited (each at `amplitude`)
  std::vector<double> velocity;    // cells: the initial v (empty: v_ss(phi) at each point)
  Segregation segregation;         // segregation only (length = 2 half_width)
};

struct Scene {
  std::string file;      // where it came from, for messages
  std::string text;      // the scene as read (stored in output files)
  std::string canonical; // its canonical text after --set (scene/canonical.hpp), for restarts
  Run run;
  Domain domain;
  Fluid fluid;
  std::optional<BodyForce> body_force;
  std::optional<Walls> walls;
  std::optional<Colloids> colloids;
  std::optional<Thermostat> thermostat;
  Output output;
  std::optional<Kmc> kmc;             // engine kmc only
  std::optional<Lgca> lgca;           // engine lgca only
  std::optional<Tagged> tagged;       // engine lgca, [tagged] given
  std::optional<LgcaColloid> colloid; // engine lgca, [colloid] given
  std::optional<Continuum> continuum; // engine continuum only
};

// The acceleration of every colloid from fields (its force is M times it): colloids.gravity,
// plus body_force.value when the body force acts on the colloids too (acts_on =
// "fluid+colloids"). Zero without [colloids].
std::array<double, 3> colloid_acceleration(const Scene &s);

// Names used in messages and files.
const char *to_string(Engine e);
const char *to_string(Collision c);
const char *to_string(LgcaModel m);

} // namespace narrows::scene
