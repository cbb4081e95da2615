// The schema of the kinetic Monte Carlo engine (kmc): its section [kmc] and its observables.
#include "schema_tables.hpp"

namespace narrows::scene::detail {

namespace {

bool always(const Scene &) { return true; }
// The shock position and the charge profile are sampled kmc.samples times.
bool sampled(const Scene &s) { return s.kmc->samples > 0; }

} // namespace

const EngineSchema &kmc_schema() {
  // Sections: {name, keys}; keys: {name, type, default, allowed, unit, meaning[, sub-keys]};
  // observables: {name, layout, meaning, written by default when[, follows the colloids]}.
  static const EngineSchema schema{
      Engine::kmc,
      {{"kmc",
        {{"length", "integer", "required", "2 (open) or 3 (periodic) to 2147483647", "sites",
          "chain length L"},
         {"boundary", "string", R"(`"open"`)", R"(`"open"`, `"periodic"`)", "", "boundary"},
         {"rates", R"(table `{ "ab->cd" = rate }`)", R"(required unless `preset = "family2"`)",
          R"(states 0-2 or Tabatabaei's labels `"w24"`; rates >= 0, at least one > 0; family 1: only its ten transitions)",
          "1/time", "bulk pair rates"},
         {"left", R"(table `{ "a->b" = rate }`)", "`{}`",
          "open boundary; also `alpha1-3`, `gamma1-3`", "1/time", "transitions of site 1"},
         {"right", R"(table `{ "a->b" = rate }`)", "`{}`",
          "open boundary; also `delta1-3`, `beta1-3`", "1/time", "transitions of site L"},
         {"initial",
          "table",
          "required unless one `kmc.fugacity` is given",
          "see the sub-keys",
          "",
          "initial measure",
          {{"kind", "string", "required", R"(`"product"`, `"shock"`)", "",
            "product measure or a shock"},
           {"probabilities", "array of 3 numbers", "from `kmc.fugacity`", ">= 0, sum 1", "",
            "product: P(n) for n = 0, 1, 2"},
           {"site", "integer", R"(required with `"shock"`)", "1 to L − 1", "site",
            "sites 1..site take `left`"},
           {"left", "array of 3 numbers", "from `kmc.fugacity`", ">= 0, sum 1", "",
            "shock: P(n) left of the shock"},
           {"right", "array of 3 numbers", "from `kmc.fugacity`", ">= 0, sum 1", "",
            "shock: P(n) right of the shock"}}},
         {"time", "number", "required", "> 0", "time",
          "simulated time observed per replica after warm-up"},
         {"warmup", "number", "0", ">= 0", "time", "simulated time before observing"},
         {"replicas", "integer", "1", "1 to 1000000 (may be raised on a restart)", "",
          "independent replicas"},
         {"charge", "array of 3 integers", "`[0, 1, 2]` (a preset may set another)",
          "each −1000 to 1000", "", "C(n) counted by the current"},
         {"samples", "integer", "100 with a shock, else 0", "0 to 100000", "",
          "shock-position samples over `kmc.time`"},
         {"preset", "string", R"(`"none"`)",
          R"(`"none"`, `"family1"` (eq 2.5), `"family2"` (eq 2.79))", "",
          "derive densities, current and shock rates, and warn about missed conditions"},
         {"parameters",
          "table",
          R"(required with `"family2"`)",
          "`c` > 0 (required), `h1`-`h6`, `r1`-`r9` >= 0 (default 0)",
          "",
          "family 2 rates (eq 2.86)",
          {{"c", "number", "required", "> 0", "", "ratio of B to A (eq 2.81)"}}},
         {"fugacity", "number or array of 2", "none", ">= 0; needs a preset; two values: a shock",
          "", "fugacity z, or [z_left, z_right]"},
         {"boundary_rates", "string", R"(`"given"`)",
          R"(`"given"`, `"fugacity"` (needs `kmc.fugacity`, open boundary, no `left`/`right`))", "",
          "boundary rates as given, or made to fit the fugacities"},
         {"boundary_coupling", "number", "1", "> 0", "1/time",
          "base rate of the generated boundary rates"},
         {"max_tries", "number", "1e12", "> 0", "tries",
          "refuse the scene (at `check` and `run`) when the expected tries per replica (sites × "
          "the largest rate out of one state × (warmup + time)) exceed this; about 1e8 tries take "
          "a second"}}}},
      {{"current",
        "`/observables/current/value [1][L−1]`, `bins [L−1]`; `current_mean [1]`, "
        "`current_boundary [1][2]`, `current_theory` with a preset",
        "time-averaged charge current through each bond", always},
       {"density_profile", "`/observables/density_profile/value [1][L][3]`, `bins [L]`",
        "occupation probability of each state per site", always},
       {"pair_correlation", "`/observables/pair_correlation/value [1][L−1][9]`, `bins [L−1]`",
        "connected correlation P(n_k = a, n_(k+1) = b) − P(a) P(b), c = 3a + b"},
       {"shock_position",
        "`/observables/shock_position/value [samples+1]`, `shock_position_variance`, `shock_theory "
        "[1][2]`",
        "mean shock position over time (needs a shock)", sampled},
       {"charge_profile", "`/observables/charge_profile/value [samples+1][L]`, `bins [L]`",
        "charge profile over time (needs `kmc.samples > 0`)", sampled}}};
  return schema;
}

} // namespace narrows::scene::detail
