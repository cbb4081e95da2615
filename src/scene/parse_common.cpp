// Validation of the sections every engine reads: [run] (the engine first, since it decides
// which other sections exist) and [output].
#include "parse_common.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace narrows::scene::detail {

using toml::value;

Engine parse_engine(const Checker &c, const value *run) {
  const value *v = find(run, "engine");
  if (v == nullptr)
    return Engine::mpcd;
  const std::vector<std::string> names{"mpcd", "lgca", "kmc", "continuum"};
  const std::string s = c.string(*v, "run.engine", "one of " + join(names));
  if (s == "mpcd")
    return Engine::mpcd;
  if (s == "kmc")
    return Engine::kmc;
  if (s == "lgca")
    return Engine::lgca;
  if (s == "continuum")
    return Engine::continuum;
  std::string msg =
      "run.engine = " + repr(*v) + " is not a known engine; allowed: mpcd, lgca, kmc, continuum";
  const std::string hint = closest(s, names);
  if (!hint.empty())
    msg += "; did you mean \"" + hint + "\"?";
  c.fail("run.engine", msg);
}

void parse_run(const Checker &c, const value *run, Run &out) {
  c.check_keys(run, "run");

  const std::string dims_allowed = "2 or 3";
  if (const value *v = find(run, "dimensions"))
    out.dimensions = static_cast<int>(c.integer(*v, "run.dimensions", "an integer, " + dims_allowed,
                                                [](std::int64_t n) { return n == 2 || n == 3; }));
  else if (out.engine == Engine::mpcd)
    c.missing("run.dimensions", dims_allowed);

  const std::string seed_allowed = "an integer >= 0";
  if (const value *v = find(run, "seed"))
    out.seed = static_cast<std::uint64_t>(
        c.integer(*v, "run.seed", seed_allowed, [](std::int64_t n) { return n >= 0; }));

  // kmc runs kmc.time per replica and has no steps: there run.steps is optional (and unused).
  // Checkpoint names hold the step in 10 digits (io/checkpoint.hpp, max_checkpoint_step).
  const std::string steps_allowed =
      "an integer from 0 to 9999999999 (the step at which the run ends)";
  if (const value *v = find(run, "steps"))
    out.steps = c.integer(*v, "run.steps", steps_allowed,
                          [](std::int64_t n) { return n >= 0 && n <= 9999999999; });
  else if (out.engine != Engine::kmc && out.engine != Engine::continuum)
    c.missing("run.steps", steps_allowed);
}

void parse_output(const Checker &c, const value *o, Engine engine, Output &out) {
  c.check_keys(o, "output");
  if (const value *v = find(o, "dir")) {
    out.dir = c.string(*v, "output.dir", "a non-empty directory path");
    if (out.dir.empty())
      c.out_of_range("output.dir", *v, "a non-empty directory path");
  }
  if (const value *v = find(o, "every"))
    out.every = c.integer(*v, "output.every", "an integer >= 1 (steps)",
                          [](std::int64_t n) { return n >= 1; });
  if (const value *v = find(o, "observables")) {
    std::vector<std::string> names;
    for (const auto &spec : engine_schema(engine).observables)
      names.emplace_back(spec.name);
    const std::string allowed = "an array of strings from: " + join(names);
    if (!v->is_array())
      c.wrong_type("output.observables", *v, allowed);
    out.observables.clear();
    const auto &a = v->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = "output.observables[" + std::to_string(i) + "]";
      const std::string s = names[c.choice(a[i], key, "a known observable", names)];
      if (std::find(out.observables.begin(), out.observables.end(), s) != out.observables.end())
        c.fail(key, key + " = " + repr(a[i]) +
                        " is listed twice; allowed: each observable at most once");
      out.observables.push_back(s);
    }
  }
  if (const value *v = find(o, "checkpoint_every"))
    out.checkpoint_every =
        c.integer(*v, "output.checkpoint_every", "an integer >= 0 (0 = only at the end)",
                  [](std::int64_t n) { return n >= 0; });
  if (const value *v = find(o, "checkpoint_keep"))
    out.checkpoint_keep = static_cast<int>(
        c.integer(*v, "output.checkpoint_keep", "an integer from 1 to 1000 (checkpoints kept)",
                  [](std::int64_t n) { return n >= 1 && n <= 1000; }));
  if (const value *v = find(o, "trajectory_every"))
    out.trajectory_every =
        c.integer(*v, "output.trajectory_every", "an integer >= 0 (steps; 0 = no trajectory)",
                  [](std::int64_t n) { return n >= 0; });
  if (const value *v = find(o, "trajectory_subsample"))
    out.trajectory_subsample =
        c.integer(*v, "output.trajectory_subsample",
                  "an integer >= 1 (frames hold the fluid particles whose id is a multiple of it)",
                  [](std::int64_t n) { return n >= 1; });
  if ((engine == Engine::kmc || engine == Engine::lgca || engine == Engine::continuum) &&
      out.trajectory_every > 0)
    c.fail("output.trajectory_every",
           "output.trajectory_every = " + std::to_string(out.trajectory_every) +
               " is for particle engines; allowed with run.engine = \"" + to_string(engine) +
               "\": 0 (the lattice engines write no trajectory)");
  if (const value *v = find(o, "axial_bin"))
    out.axial_bin = c.number(*v, "output.axial_bin", "a number > 0 (cell units)",
                             [](double x) { return x > 0.0; });
  if (const value *v = find(o, "kde_window"))
    out.kde_window = c.integer(*v, "output.kde_window",
                               "an integer >= 0 (steps; 0 = one average over the whole run)",
                               [](std::int64_t n) { return n >= 0; });
  if (out.kde_window > 0 && out.kde_window % out.every != 0)
    c.fail("output.kde_window",
           "output.kde_window = " + std::to_string(out.kde_window) +
               " is not a multiple of output.every = " + std::to_string(out.every) +
               "; allowed: 0 or a multiple of output.every (each window "
               "holds whole samples)");
  if (engine != Engine::mpcd && out.kde_window > 0)
    c.fail("output.kde_window", "output.kde_window = " + std::to_string(out.kde_window) +
                                    " windows the mpcd colloid profiles; allowed with "
                                    "run.engine = \"" +
                                    to_string(engine) + "\": 0");
  if (const value *v = find(o, "progress")) {
    if (!v->is_boolean())
      c.wrong_type("output.progress", *v, "true or false");
    out.progress = v->as_boolean();
  }
}

} // namespace narrows::scene::detail
