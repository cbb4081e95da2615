// The schema of the lattice-gas engine (lgca): its sections [lattice], [tagged] and [colloid], and
// its observables.
#include "schema_tables.hpp"

namespace narrows::scene::detail {

namespace {

bool always(const Scene &) { return true; }
bool with_tagged(const Scene &s) { return s.tagged.has_value(); }
bool with_colloid(const Scene &s) { return s.colloid.has_value(); }

} // namespace

const EngineSchema &lgca_schema() {
  // Sections: {name, keys}; keys: {name, type, default, allowed, unit, meaning[, sub-keys]};
  // observables: {name, layout, meaning, written by default when[, follows the colloids]}.
  static const EngineSchema schema{
      Engine::lgca,
      {{"lattice",
        {{"model", "string", "required",
          R"(`"fhp-i"`, `"fhp-ii"`, `"fhp-iii"`, `"fhp-saturated"`, `"dhumieres-1d"`)", "",
          "the model"},
         {"size", "array of integers", "required",
          "FHP: `[size_x, size_y]`, 2 to 1048576, size_y even; 1D: `[L]`", "sites",
          "lattice size (MPI slabs along x)"},
         {"density", "number", "required", "0 < d < 1", "", "mean occupation per link d"},
         {"initial", "string", R"(`"equilibrium"`)",
          R"(FHP: `"equilibrium"`, `"shear-wave"`; 1D: `"equilibrium"`, `"zero-momentum"`)", "",
          "initial state"},
         {"amplitude", "number", R"(0.05 with `"shear-wave"`, else 0)",
          R"(0 to min(d, 1 − d) 3/(b d) (b = 6 or 7 links), non-zero only with `"shear-wave"`)",
          "lattice velocity", "u_x = amplitude sin(2π y / L_y)"},
         {"walls", "boolean", "`false`", "FHP only", "",
          "solid rows y = 0 and y = size_y − 1 (bounce-back)"},
         {"body_force", "number", "0", "0 to 1; FHP only", "probability per site and step",
          "move a particle from link 3 (−x) to link 0 (+x)"},
         {"obstacles", "array of `[x, y, radius]`", "`[]`", "radius > 0; FHP only", "sites",
          "solid discs (bounce-back)"},
         {"block", "integer", "the largest of 8, 4, 2, 1 dividing both sizes",
          ">= 1, divides both sizes; FHP only", "sites",
          "side of the square blocks of the `density` and `velocity` fields"}}},
       {"tagged",
        {{"max_lag", "integer", "required", "1 to 1000000", "steps",
          "tagged-particle VACF by moment propagation, lags 0..max_lag"},
         {"replicas", "integer", "1", R"(1 to 10000; only with `"dhumieres-1d"`)", "",
          "independent runs of the 1D model (spread over the ranks)"}}},
       {"colloid",
        {{"position", "array `[x, y]`", "required", "finite", "lattice coordinates",
          "initial centre"},
         {"radius", "number", "2.5", "0.5 to a quarter of the smaller size; >= 0.5774 when moving",
          "sites", "disc radius"},
         {"mass", "number", "680", "> 0", "particle masses", "disc mass M"},
         {"velocity", "array `[v_x, v_y]`", "`[0, 0]`", "each component in (−1, 1)",
          "lattice velocity", "initial velocity"},
         {"held", "boolean", "`true`", "`false` not with walls or obstacles", "",
          "held in place (velocity evolves, centre stays) or moving"},
         {"max_lag", "integer", "1000", "1 to 10000000", "steps", "colloid VACF lags 0..max_lag"},
         {"displacement_lag", "integer", "5000",
          "1 to 10000000, a multiple of `displacement_every`", "steps", "D(t) up to this lag"},
         {"displacement_every", "integer", "100", "1 to 10000000", "steps",
          "D(t) at lags that are multiples of it"}}}},
      {{"shear_wave", "`/observables/shear_wave/value [T]`",
        "amplitude of the x-velocity mode sin(2π y / L_y)", always},
       {"density", "`/observables/density/value [T][size_y/block][size_x/block]`",
        "mean density per block"},
       {"velocity", "`/observables/velocity/value [T][size_y/block][size_x/block][2]`",
        "mean velocity per block"},
       {"vacf",
        "`/observables/vacf/{value, lags, error, corrected} [max_lag+1]` and scalars (`particles`, "
        "`one_step_theory`, `boltzmann_diffusion`, `mean_free_time`, ...; 1D: `plateau`, "
        "`replicas`, ...)",
        "tagged VACF Z(t) = ⟨v(0)·v(t)⟩/⟨v²⟩ (needs `[tagged]`)", with_tagged},
       {"colloid_vacf",
        "`/observables/colloid_vacf/{value, lags, error, corrected} [max_lag+1]`, "
        "`corrected_blocks`, `mean_square_velocity`, `plateau`",
        "colloid VACF (needs `[colloid]`)", with_colloid},
       {"colloid_diffusion",
        "`/observables/colloid_diffusion/{value, lags, error, corrected} "
        "[displacement_lag/displacement_every+1]`, `corrected_blocks`",
        "colloid D(t) (needs `[colloid]`)", with_colloid}}};
  return schema;
}

} // namespace narrows::scene::detail
