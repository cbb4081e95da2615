// The schema of the MPCD engine: its sections [domain], [fluid], [body_force], [walls],
// [thermostat] and [colloids], and its observables.
#include "schema_tables.hpp"

namespace narrows::scene::detail {

namespace {

bool always(const Scene &) { return true; }

} // namespace

const EngineSchema &mpcd_schema() {
  // Sections: {name, keys}; keys: {name, type, default, allowed, unit, meaning[, sub-keys]};
  // observables: {name, layout, meaning, written by default when[, follows the colloids]}.
  static const EngineSchema schema{
      Engine::mpcd,
      {{"domain",
        {{"size", "array of `run.dimensions` numbers", "required",
          "whole numbers from 2 to 1048576 each", "cells",
          "box along x (flow axis, periodic, split into MPI slabs), y [, z]"},
         {"balance", "string", R"(`"none"`)", R"(`"none"`, `"work"`, `"time"`)", "",
          "slabs of equal numbers of cell columns, or boundaries moved so that the counted work "
          "of the ranks is even (`\"work\"`: fluid particles, colloids, contacts, bounce-back "
          "events and ghost particles, weighted by their measured cost) or their measured busy "
          "time (`\"time\"`: the step's time less its messages and waiting; each rank gets a "
          "share of the counted work in proportion to the work it did per busy second, for "
          "cores of unequal speed and work the counts miss): at the start and on a restart by "
          "the counted work, then every `balance_every` steps; the results are bitwise the "
          "same, the log's `counted work` and `busy time` lines give the imbalance; a restart "
          "may change it"},
         {"balance_every", "integer", "0", "0 to 2147483647", "steps",
          "measure the counted work's and the busy time's max/mean over the ranks every this "
          "many steps (one small collective; the log lists each) and, with `\"work\"` or "
          "`\"time\"`, move the slabs when the one balanced exceeds `balance_threshold`; 0: no "
          "checks (the slabs are balanced at the start and on a restart only)"},
         {"balance_threshold", "number", "1.05", ">= 1", "",
          "with `\"work\"` or `\"time\"` and `balance_every` > 0: the max/mean of the counted "
          "work or of the busy time over the last `balance_every` steps above which the slabs "
          "move"}}},
       {"fluid",
        {{"collision", "string", "required",
          R"(`"srd"`, `"at"`, `"at+a"`, `"random-permute"`, `"random-maxwell"`)", "",
          "collision rule (MPC-AT+a conserves angular momentum)"},
         {"density", "number", "10", "> 0; fewer than 2^40 particles in total",
          "particles per cell", "mean number density n"},
         {"dt", "number", "required",
          "> 0 (`narrows check` warns when the mean free path is too small for the rule)", "time",
          "collision time step"},
         {"angle", "number", "90", "0 < angle < 360", "degrees",
          "SRD rotation angle (accepted and ignored by the other rules)"},
         {"kT", "number", "1",
          "> 0, at most 1e6 (`check`: above it thermal speeds reach the run's speed limit 1e4)",
          "energy", "temperature"},
         {"sort_every", "integer", "20", "0 to 2147483647", "steps",
          "counting sort of the particles by cell every this many steps (0: never); does not "
          "change results"}}},
       {"body_force",
        {{"kind", "string", R"(`"constant"`)", R"(`"constant"`, `"sine"` (not with `[walls]`))", "",
          "constant acceleration, or Kolmogorov flow"},
         {"value", "array of `run.dimensions` numbers", R"(required with `"constant"`)", "finite",
          "acceleration", "force per unit mass on every fluid particle"},
         {"amplitude", "number", R"(required with `"sine"`)", "finite", "acceleration",
          "a_x = amplitude sin(2π y / L_y)"},
         {"acts_on", "string", R"(`"fluid"`)",
          R"(`"fluid"`, `"fluid+colloids"` (only with `[colloids]` and `"constant"`))", "",
          "what the force drives: the fluid alone (Kanehl (thesis) §5.1: a constant force on each "
          "fluid particle), or also each colloid with M × value (a pressure gradient σ = ρ value "
          "pushes a colloid with σV, i.e. M × value for a neutrally buoyant colloid), in addition "
          "to `colloids.gravity`"}}},
       {"walls",
        {{"slip", "boolean", "`false`", "", "",
          "specular reflection instead of no-slip bounce-back"},
         {"virtual_particles", "boolean", "`true`", "", "",
          "fill cells cut by a wall to the mean density (Tabatabaei (2008) eq 3.14)"},
         {"virtual_flow", "string", R"(`"rest"`)",
          R"(`"rest"`, `"mirror"` (`"mirror"` only with no-slip walls))", "",
          "mean velocity of the virtual particles: at rest with the wall, or the mirror image of "
          "the flow next to it (slip below 1 %)"}}},
       {"thermostat",
        {{"kind", "string", "required",
          R"(`"layers"` (eq 3.53-3.54), `"monte-carlo"` (eq 3.55-3.57))", "",
          "rescale relative velocities per layer of cells across the channel, or per cell with a "
          "Monte Carlo step"},
         {"gamma", "number", "0.1", R"(0 < gamma <= 1; only with `"monte-carlo"`)", "",
          "step of the Monte Carlo scaling factor 1 + ε, ε uniform in [0, gamma]"}}},
       {"colloids",
        {{"radius", "number", "required", "> 0", "cells", "mean radius r_c"},
         {"radius_sd", "number", "0", "0 to 0.2 radius", "cells",
          "standard deviation of the radii (Gaussian truncated at ±3 sd)"},
         {"mass", "number", "fluid mass density × own volume", "> 0", "particle masses",
          "mass of each colloid"},
         {"count", "integer", R"(required with `"lattice"` and `"random"`)",
          "1 to 1000000; a lattice row must fit along x; < 90 % of the box volume", "",
          "number of colloids"},
         {"placement", "string", R"(`"lattice"`)",
          R"(`"lattice"` (a row along x), `"random"` (no overlap), `"list"`, `"file"`, `"packing"` (a dense packing grown from points, below; only with `coupling = "no-slip"`))",
          "", "how colloids are placed"},
         {"positions", "array of `[x, y(, z)]`", R"(required with `"list"`)",
          "inside the box, off the walls, cores not overlapping", "cells", "given centres"},
         {"positions_file", "string", R"(required with `"file"`)",
          "a text file (relative to the scene), one `x y [z]` per line, `#` comments", "",
          "given centres from a file"},
         {"gravity", "array of `run.dimensions` numbers", "`[0, 0(, 0)]`", "finite", "acceleration",
          "field g: each colloid feels M g, the fluid none (a pressure-gradient drive of the "
          "colloids is `body_force.acts_on` instead)"},
         {"md_substeps", "integer", "15", "1 to 10000", "",
          "velocity-Verlet steps per collision step (τ_MD = dt / md_substeps)"},
         {"epsilon", "number", "1", "> 0", "kT", "strength of all colloid potentials"},
         {"wall_sigma", "number", "2 r_a",
          "> 0 with cut-off 1.0631 wall_sigma < L_y / 2; only with `[walls]`", "cells",
          "σ_w of the colloid-wall potential"},
         {"wall_q", "number", "1", "> 0", "", "q of the wall potential (eq 3.35)"},
         {"coupling", "string", R"(`"md"`)", R"(`"md"`, `"no-slip"`)", "",
          "how colloids meet the fluid (above)"},
         {"contacts", "string", R"(`"none"`)",
          R"(`"none"`, `"hard"`, `"spring"` (both only with `"no-slip"`))", "",
          "colloid-colloid and colloid-wall contacts: none, event-driven rough hard spheres "
          "(Kanehl (thesis) §4.2.2: earliest collision first, normal and tangential contact "
          "velocity reversed; walls are rough and at rest), or linear springs with Coulomb "
          "friction and contact history (Kanehl (thesis) §4.2.3, `[colloids.spring]` below)"},
         {"exchange", "string", R"(`"implicit"`)",
          R"(`"implicit"`, `"explicit"` (only with `"no-slip"`))", "",
          "how a no-slip colloid takes the impulses of bounce-back and ghost particles: "
          "implicit (midpoint rule, (M + G/2) ΔX = ΔP with G the fluid's linear response, and "
          "the fluid that gave the impulse shifted by G ΔX/2: kT per degree of freedom, "
          "momentum and angular momentum exact) or explicit (ΔX = ΔP/M, Kanehl (thesis) eq "
          "4.16-4.17 as written; the colloid runs hot by up to 1/(1 - G/2M))"},
         {"kind",
          "array of tables `[[colloids.kind]]`",
          "none (one kind from `radius`, `count`, `mass`)",
          R"(one table per kind with `radius`, `count` and optional `mass` (below); not with `colloids.radius`, `radius_sd`, `mass`, `count`; placement `"lattice"`, `"random"` or `"packing"`)",
          "",
          "several colloid kinds (bidisperse, polydisperse)",
          {{"radius", "number", "required", "> 0", "cells", "radius of this kind"},
           {"count", "integer", "required", "1 to 1000000 (all kinds together too)", "",
            R"(number of colloids of this kind (with `"packing"`: its share in the number ratio, scaled to the packing fraction); ids are given kind by kind in the order of the tables)"},
           {"mass", "number", "fluid mass density × own volume", "> 0", "particle masses",
            "mass of each colloid of this kind"}}},
         {"spring",
          "table `[colloids.spring]`",
          "the defaults below",
          R"(only with `contacts = "spring"`)",
          "",
          "constants of the spring contacts: F_n = −k_n δ_n, tangential spring F_t = −k_t ξ kept "
          "per contact while it lasts (turned into the tangent plane and stretched by the "
          "tangential contact velocity each sub-step), the magnitude of F_t at most μ times that "
          "of F_n (beyond: sliding); torques r n × F_t on both bodies; walls at rest. No damping: "
          "Kanehl (thesis) has none (σ of its Table 6.1 is the pressure gradient), the fluid damps "
          "collisions",
          {{"kn", "number", "2500", "> 0", "kT / a²",
            "normal spring constant k_n (Kanehl (thesis) Table 6.1)"},
           {"kt", "number", "2500", ">= 0", "kT / a²",
            "tangential spring constant k_t (Kanehl (thesis) Table 6.1)"},
           {"mu_cc", R"(number or `"inf"`)", "1",
            R"(>= 0, or `"inf"` (also the TOML float `inf`): never slides)", "",
            "colloid-colloid friction coefficient μ (Kanehl (thesis) §6.2.1: μ = 1)"},
           {"mu_cw", R"(number or `"inf"`)", "1", R"(>= 0, or `"inf"`)", "",
            "colloid-wall friction coefficient μ_cw"},
           {"substeps", "integer", "10",
            "1 to 10000, with ω h ≤ 0.25 for the stiffest contact of the lightest colloids (ω² = "
            "max(k_n, 3 k_t (2D) or 3.5 k_t (3D)) / (M/2), h = dt / substeps)",
            "", "velocity-Verlet sub-steps of the contacts per MPCD step"}}},
         {"max_lag", "integer", "1000", "a multiple of `correlation_every`, at most 100000 of them",
          "steps", "colloid VACF, D(t), MSD and angular VACF for lags 0..max_lag"},
         {"correlation_every", "integer", "1", "1 to 1000000", "steps",
          "colloid velocities, positions and angular velocities are sampled every this many steps "
          "for the correlations"},
         {"kde_width", "number", "0.25", "> 0", "cells",
          "half-width ε of the Epanechnikov kernel of `density_kde` (Kanehl (thesis) eq 5.2)"},
         {"statistics_from", "integer", "0", ">= 0", "step",
          "the colloid statistics (correlations, `density_kde`) start at this step (skip the "
          "transient)"},
         {"packing_fraction", "number", R"(required with `"packing"`)",
          R"(> 0 and at most 0.84 (2D) or 0.64 (3D), random close packing; only with `"packing"`)",
          "",
          "target area (volume) fraction of the colloids in the box; it sets the number of "
          "colloids: one kind round(φ V / v(r)) (`count` and `radius_sd` refused), several kinds "
          "their `count`s (read as the number ratio) times one common factor, each rounded"},
         {"packing_max_work", "number", "1e9", R"(> 0; only with `"packing"`)", "",
          "refuse the scene (at `check` and `run`) when the estimated work of its packing, N (10⁴ "
          "+ N) colloid-steps for N colloids, exceeds this; about 10⁷ colloid-steps take a second, "
          "on every rank alike"}}}},
      {{"temperature", "`/observables/temperature/value [T]`",
        "kT of the fluid relative to the cell means", always},
       {"momentum", "`/observables/momentum/value [T][d]`", "total momentum, fluid + colloids",
        always},
       {"velocity_profile", "`/observables/velocity_profile/value [T][bins][d]`, `bins [bins]`",
        "mean velocity binned across y", always},
       {"density_profile", "`/observables/density_profile/value [T][bins]`, `bins [bins]`",
        "number density binned across y", always},
       {"viscosity", "`/observables/viscosity/value [T]`",
        "ν fitted to the Poiseuille profile (needs `[walls]` and a non-zero x force)"},
       {"energy", "`/observables/energy/value [T]`", "total energy, with the colloid potentials"},
       {"settling_velocity", "`/observables/settling_velocity/value [T][d]`",
        "mean colloid velocity in the co-moving frame (eq 4.8-4.10; needs `[colloids]`)", nullptr,
        true},
       {"colloid_positions",
        "`/observables/colloid_positions/value [T][N_c][d]`, `bins [N_c]` (colloid ids)",
        "colloid centres (needs `[colloids]`)", nullptr, true},
       {"axial_fields",
        "`/observables/axial_fields/{phi, velocity, fluid_velocity} [T][bins]`, `bins [bins]` "
        "(x centres), `step`, `time`",
        "fields along the channel averaged over its cross-section in bins of "
        "`output.axial_bin` (Kanehl (thesis) eq 6.1): colloid area fraction φ from the power "
        "(Voronoi) cells of the colloids, their material-weighted x-velocity, the fluid's mean "
        "x-velocity (3D: volume fraction; needs `[colloids]`)",
        nullptr, true},
       {"colloid_vacf",
        "`/observables/colloid_vacf/{value, lags, error} [max_lag/correlation_every+1]`, "
        "`value_by_kind`, `error_by_kind` (`[kinds][lags]` row-major, stored flat), `kinds`, "
        "`samples`",
        "C(τ) = ⟨v(t)·v(t+τ)⟩ (Kanehl (thesis) eq 4.50) over all colloids and per kind; `lags` τ "
        "in time units",
        nullptr, true},
       {"colloid_diffusion",
        "`/observables/colloid_diffusion/{value, lags, error}`, `value_by_kind`, `error_by_kind`",
        "D(t) = (1/d) ∫₀ᵗ C(τ) dτ (eq 4.51, trapezoid rule)", nullptr, true},
       {"colloid_msd",
        "`/observables/colloid_msd/{value, lags, error}`, `value_by_kind`, `error_by_kind`",
        "⟨|r(t+τ) − r(t)|²⟩ of the unwrapped centres", nullptr, true},
       {"colloid_angular_vacf",
        "`/observables/colloid_angular_vacf/{value, lags, error}`, `value_by_kind`, "
        "`error_by_kind`, `integral`, `integral_error`, `integral_by_kind`",
        "⟨ω(t)·ω(t+τ)⟩ and D_rot(t) = (1/d_rot) ∫₀ᵗ (d_rot = 1 in 2D, 3 in 3D)", nullptr, true},
       {"contact_statistics",
        "`/observables/contact_statistics/value [T][2][100]` (overlap counts: colloid-colloid, "
        "colloid-wall), `bins [100]` (δ/a), `bin_width`, `contacts [T][2]`, `beyond [T][2]`, "
        "`sliding_fraction [T][2]`, `coordination [T][kinds]`",
        "spring contacts at each sample (Kanehl (thesis) fig 6.2a): histogram of the normal "
        "overlaps δ/a (a the smaller radius, a colloid's own at a wall) in bins of 0.002 from 0 "
        "to 0.2 (`beyond`: deeper), the fraction of contacts sliding (|F_t| at μ|F_n|), the mean "
        "number of colloid partners per colloid of each kind (needs `contacts = \"spring\"`)",
        nullptr, true},
       {"density_kde",
        "`output.kde_window` = 0: `/observables/density_kde/{value, error} [kinds][bins]`, "
        "`bins [bins]` (y), `width`, `counts [kinds]`, `samples`; > 0: `value "
        "[windows][kinds][bins]`, `step`, `time` (the window's end), `samples [windows]`, "
        "`bins`, `width`, `counts` (no `error`)",
        "per-kind kernel density profile across y, eq 5.2 with ε = `colloids.kde_width`, "
        "normalised to 1 per kind, time average of samples every `output.every` steps (over the "
        "whole run, or over each window of `output.kde_window` steps)",
        nullptr, true},
       {"evolution",
        "`/observables/evolution/value [windows]`, `by_kind [windows][kinds]`, `step`, `time`",
        "Δ(t) of Kanehl (thesis) eq 5.31 per `density_kde` window, against the first window: "
        "`value` of the total number density Σ_k N_k F_k(y), `by_kind` of each F_k alone (needs "
        "`density_kde` and `output.kde_window` > 0); the run log ends with the steady-state "
        "criterion",
        nullptr, true},
       {"colloid_velocity_profile",
        "`/observables/colloid_velocity_profile/{value, weight} [windows][kinds][bins]`, `step`, "
        "`time`, `bins [bins]` (y)",
        "per kind the kernel-weighted mean x velocity of the colloids across y, "
        "Σ K(y − y_i) v_x,i / Σ K(y − y_i) over the window's samples (kernel and bins of "
        "`density_kde`; NaN where the weight is 0), per `output.kde_window` window (0: one "
        "window, the whole run, written at the end)",
        nullptr, true}}};
  return schema;
}

} // namespace narrows::scene::detail
