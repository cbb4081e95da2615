// The schema of the continuum engine: its section [continuum] and its observables.
#include "schema_tables.hpp"

namespace narrows::scene::detail {

namespace {

bool always(const Scene &) { return true; }
bool conservation_law(const Scene &s) {
  return s.continuum->model == ContinuumModel::conservation_law;
}
bool jamming(const Scene &s) { return s.continuum->model == ContinuumModel::jamming; }
bool segregation(const Scene &s) { return s.continuum->model == ContinuumModel::segregation; }

} // namespace

const EngineSchema &continuum_schema() {
  // Sections: {name, keys}; keys: {name, type, default, allowed, unit, meaning[, sub-keys]};
  // observables: {name, layout, meaning, written by default when[, follows the colloids]}.
  static const EngineSchema schema{
      Engine::continuum,
      {{"continuum",
        {{"model", "string", "required", R"(`"conservation-law"`, `"jamming"`, `"segregation"`)",
          "", "the model"},
         {"flux", "string", "required",
          R"(`"burgers"`, `"tasep"`, `"family1"`, `"family2"`, `"colloid-chain"`)", "",
          "J(rho): rho²/2; (p − q) rho (1 − rho); family 1's charge current eq 2.48 at rho*(sigma) "
          "of eq 2.59 (eq 2.60, density = charge sigma in [−1, 1]); family 2's particle current eq "
          "2.126; the colloid chain rho (c rho + c′ − v_cm) (eq 5.3). The lattice-gas fluxes are "
          "the kmc presets' formulas"},
         {"rates", R"(table `{ "ab->cd" = rate }`)",
          R"(tasep: `{ "10->01" = 1 }`; required with family1)",
          R"(as `kmc.rates`; tasep: only `"10->01"` (p) and `"01->10"` (q); family1: its ten transitions)",
          "1/time", "the lattice gas's pair rates (tasep, family1)"},
         {"parameters",
          "table",
          "required with family2",
          "as `kmc.parameters` (`c` > 0, `h1`-`h6`, `r1`-`r9` >= 0)",
          "",
          "family 2 rates (eq 2.86)",
          {{"c", "number", "required", "> 0", "", "ratio of B to A (eq 2.81)"}}},
         {"c", "number", "5.71", "finite; colloid-chain only", "velocity × length",
          "c of eq 5.2 (Tabatabaei (2008) fig 5.1)"},
         {"c_prime", "number", "0.019", "finite; colloid-chain only", "velocity",
          "c′ of eq 5.2 (Tabatabaei (2008) fig 5.1)"},
         {"v_cm", "number", "0", "finite; colloid-chain only", "velocity",
          "centre-of-mass velocity v_cm of eq 5.2"},
         {"length", "number", "required", "> 0", "length (sites)", "domain [0, length]"},
         {"cells", "integer", "required",
          "4 to 100000000; jamming: even, 8 to 16777216; segregation: even, 4 to 1000000", "",
          "finite-volume cells (jamming: grid points; segregation: across [−w, w])"},
         {"diffusion", "number", "0; jamming: 1", ">= 0; jamming: > 0", "length²/time",
          "D (explicit; limits the time step; jamming: exact in Fourier space)"},
         {"boundary", "string", R"(`"open"`; jamming: `"periodic"`)",
          R"(`"open"` (reservoirs at fixed densities), `"periodic"`; jamming: `"periodic"`)", "",
          "boundary"},
         {"reservoirs", "array `[left, right]`", "the initial densities at the two ends",
          "densities of the flux's range; open only", "",
          "densities held left of 0 and right of length"},
         {"initial",
          "table",
          "required",
          "see the sub-keys",
          "",
          "initial data (cell averages of it)",
          {{"kind", "string", "required",
            R"(`"riemann"`, `"profile"`, `"sine"`, `"cells"`; jamming: `"sine"`, `"random"`, `"cells"`, `"eigenmode"`)",
            "",
            "a jump, a piecewise-linear profile, a sine, or the cell averages themselves; jamming: "
            "phi at the points, v = v_ss(phi) unless `velocity` is given; `\"eigenmode\"`: each of "
            "`modes` on the growing eigenvector of eq 6.10 (phi and v)"},
           {"left", "number", R"(required with `"riemann"`)",
            "the flux's range: family1 −1 to 1; tasep, family2 0 to 1; others finite", "",
            "density left of the jump"},
           {"right", "number", R"(required with `"riemann"`)", "as `left`", "",
            "density right of the jump"},
           {"position", "number", "length / 2", "0 to length", "length", "where the jump is"},
           {"values", "array of numbers", R"(required with `"profile"` and `"cells"`)",
            "in the flux's range; profile: 2 to 10000000 values; cells: `cells` values", "",
            "profile: values at equally spaced points from 0 to length, joined linearly; cells: "
            "the initial cell averages (e.g. a coarse-grained kmc profile)"},
           {"mean", "number", R"(required with `"sine"` (and jamming `"random"`, `"eigenmode"`))",
            "in the flux's range; jamming: 0 < mean < 1", "",
            "mean of mean + amplitude sin(2π x / length) (jamming: of phi)"},
           {"amplitude", "number",
            R"(required with `"sine"` (and jamming `"random"`, `"eigenmode"`))",
            "mean ± amplitude in the flux's range; jamming: in [0, 1]; eigenmode: >= 0, mean ± "
            "(number of modes) × amplitude in [0, 1]",
            "",
            R"(amplitude of the sine; jamming `"random"`: phi_i = mean + amplitude u_i, u_i uniform in (−1, 1) at each point; `"eigenmode"`: of phi in each mode (1e-6 or less: the modes feed each other at order amplitude², which tools/jamming_plot.py keeps under 1e-3 of a mode it measures))"},
           {"mode", "integer", "1", R"(1 to (cells − 1) / 3; jamming `"sine"` only)", "",
            "n of phi = mean + amplitude sin(2π n x / length)"},
           {"modes", "array of integers", "every mode 1 to (cells − 1) / 3",
            R"(distinct, 1 to (cells − 1) / 3; jamming `"eigenmode"` only)", "",
            "the modes n (k = 2π n / length) of phi = mean + amplitude Σ_n cos(k x + θ_n), v = "
            "v_ss(mean) + amplitude Σ_n Re(r_n e^(i(k x + θ_n))), r_n = −(λ_n + i k v0 + D k²) / "
            "(i "
            "k phi0) on the eigenvalue λ_n of larger real part (eq 6.11): each mode grows (decays) "
            "at "
            "Re λ_n from t = 0, without the transient of the fast mode"},
           {"seed", "integer", "1", R"(>= 0; jamming `"random"`, `"eigenmode"` only)", "",
            "seed of the random perturbation (the same on any rank count); eigenmode: of the "
            "phases θ_n"},
           {"velocity", "array of numbers", "v_ss(phi) at each point",
            R"(`cells` finite numbers; jamming `"cells"` only)", "length/time",
            "v at the points"}}},
         {"time", "number", "required", "> 0", "time", "simulated time"},
         {"samples", "integer", "100", "1 to 100000", "",
          "samples of the observables over `time` (and one at t = 0)"},
         {"cfl", "number", "0.4; jamming: 0.1", "0 < cfl <= 0.5", "",
          "Courant number of the time step (jamming: the Strang splitting's error in growth rates "
          "is second order, under 1 % at 0.1, 6 % at 0.4)"},
         {"max_work", "number", "1e11", "> 0", "",
          "refuse the scene (at `check` and `run`) when its grid points × time steps exceed this "
          "(each step advances every point); about 1e7 point-steps take a second"},
         {"limiter", "string", R"(`"mc"`)",
          R"(`"mc"` (monotonised central), `"minmod"`; conservation-law only)", "",
          "TVD slope limiter"},
         {"mu", "string", R"(`"1"` (unless `vss` or `vss_fit`))",
          R"(`"infinity"`, `"1"`, `"1/2"`, `"0"`; jamming only; not with `vss`, `vss_fit`)", "",
          "wall friction mu: the column of Table 6.2 whose v_ss(phi) fit (eq 6.4) gives xi = sigma "
          "/ v_ss"},
         {"vss",
          "table",
          "none",
          "jamming only; not with `mu`, `vss_fit`; all six sub-keys; delta_v >= 0, delta_phi > 0, "
          "0 < phi_c < phi_q <= 1, e1 > 0, e1 + e2 phi_c > 0",
          "",
          "the parameters of the v_ss(phi) fit (eq 6.4) given explicitly (Table 6.2's column mu = "
          "1 is `{ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = −3.24, "
          "phi_q = 0.845 }`); e3 follows from continuity at phi_c",
          {{"delta_v", "number", "required", ">= 0", "velocity",
            "Delta v, height of the tanh step"},
           {"delta_phi", "number", "required", "> 0", "", "Delta phi, width of the tanh step"},
           {"phi_c", "number", "required", "0 < phi_c < phi_q", "", "phi_c, the jamming point"},
           {"e1", "number", "required", "> 0", "velocity", "e1 of the free-flow line e1 + e2 phi"},
           {"e2", "number", "required", "e1 + e2 phi_c > 0", "velocity",
            "e2 of the free-flow line"},
           {"phi_q", "number", "required", "phi_c < phi_q <= 1", "",
            "phi_q, where the jammed branch e3 (phi − phi_q)² vanishes"}}},
         {"vss_fit", "string", "none",
          "jamming only; not with `mu`, `vss`; a readable JSON file (see below)", "",
          "path (relative to the scene file) of a JSON object with the numbers `delta_v`, "
          "`delta_phi`, `phi_c`, `e1`, `e2`, `phi_q` of eq 6.4 (optional `<name>_error` numbers "
          ">= 0, other keys ignored), as tools/vss_fit.py writes it; the same ranges as `vss`"},
         {"drive", "number", "1", "> 0; jamming only", "length/time²",
          "sigma of eq 6.3, the driving acceleration (1: the normalised eq 6.6)"},
         {"dimensions", "integer", "2", "2 or 3; segregation only", "",
          "d of eq 5.13 and the structure factor (eq 5.19–5.20 or 5.21–5.22); sets the defaults of "
          "`k_d` and `max_packing`"},
         {"half_width", "number", "required with segregation", "> 0", "length",
          "w: the walls are at y = −w and +w"},
         {"centre_speed", "number", "required with segregation", ">= 0", "length/time",
          "v0, centre speed of the Poiseuille flow (shear rate 2 v0 |y| / w²)"},
         {"shear", "string", R"(`"poiseuille"`)",
          R"(`"poiseuille"`, `"viscous"`; segregation only)", "",
          "the shear rate: of the Newtonian Poiseuille flow, or of a constant pressure gradient in "
          "the local viscosity eta(phi) (the same for a uniform suspension)"},
         {"k_c", "number", "1", "> 0; segregation only", "",
          "K_c of eq 5.3 (collision-frequency drift)"},
         {"k_eta", "number", "1.51", ">= 0; segregation only", "",
          "K_eta of eq 5.3 (viscosity-gradient drift; Kanehl (thesis): K_eta / K_c = 1.51)"},
         {"k_d", "number", "7.46 (2D), 0.61 (3D)", "> 0; segregation only", "",
          "K_d of eq 5.23, D_C = K_d D_0 / S(phi) (Kanehl (thesis): K_d / K_c = 7.46 in 2D, 0.61 "
          "in 3D)"},
         {"max_packing", "number", "0.82 (2D), 0.64 (3D)", "0 < phi_M < 1; segregation only", "",
          "phi_M of eq 5.29"},
         {"kind",
          "array of tables `[[continuum.kind]]`",
          "required with segregation",
          "one or two kinds",
          "",
          "the colloid kinds (output order)",
          {{"radius", "number", "required", "> 0 and < `half_width`", "length", "a_i"},
           {"fraction", "number", "required", "> 0, all kinds together < `max_packing`", "",
            "mean area (volume) fraction of the kind over the channel"},
           {"diffusivity", "number", "required", "> 0", "length²/time",
            "single-colloid diffusivity D_0^i"}}}}}},
      {
          {"density",
           "`/observables/density/value [samples+1][cells]`, `bins [cells]` (cell centres; "
           "jamming: the points i length / cells), `step`, `time`; segregation with two kinds: "
           "`value [samples+1][cells][2]`, bins the y of the cell centres",
           "cell averages of the density (jamming: phi at the points; segregation: phi_i of each "
           "kind)",
           always},
          {"shock_position", "`/observables/shock_position/value [samples+1]`, `time`",
           "conservation-law only: position of the steepest jump (where the profile crosses the "
           "mid level of the densities 4 cells either side of it)",
           conservation_law},
          {"velocity",
           "`/observables/velocity/value [samples+1][cells]`, `bins [cells]`, `step`, `time`",
           "jamming only: v at the points", jamming},
          {"evolution", "`/observables/evolution/value [samples+1]`, `step`, `time`",
           "segregation only: Delta(t) of eq 5.31 from the total number density (sum phi_i / "
           "a_i^d)",
           segregation},
          {"steady_density",
           "`/observables/steady_density/value [cells][kinds]`, `bins [cells]`, `step`, `time`",
           "segregation only: the steady profile phi_i at the cell centres (shooting, see above), "
           "written once per observables file",
           segregation},
          {"collective_diffusivity",
           "`/observables/collective_diffusivity/value [phis][kinds][kinds]`, `bins [phis]`, "
           "`structure_factor [phis]`, `viscosity [phis]`, `composition [kinds]`, `scale "
           "[kinds]`, `step`, `time`",
           "segregation only: the model's coefficients against the total fraction phi (`bins`: "
           "200 points k phi_M / 200, 0 to just below phi_M) at the scene's composition (kind i "
           "at phi_i = phi f_i, `composition` f_i = its share of the mean fractions): `value` "
           "D_C^ij / (K_d D_0^i) of eq 5.23-5.28 (diagonal 1 / S(phi), off-diagonal phi_i / ((1 "
           "- phi_j)^2 S(phi)); Kanehl (thesis) fig 5.3 is the diagonal in 2D at c_L = c_S, "
           "a_L / a_S = 2), `scale` K_d D_0^i (D_C^ij = value scale_i), `structure_factor` "
           "S(phi) of eq 5.19-5.22, `viscosity` eta / eta_0 of eq 5.29; written once per "
           "observables file; tools/segregation_theory.py draws them",
           nullptr, false, segregation},
      }};
  return schema;
}

} // namespace narrows::scene::detail
