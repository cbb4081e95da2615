// The scene schema put together: [run] and [output], which every engine reads, the engines'
// own schemas (schema_<engine>.cpp), and the look-ups parse_scene and the docs test make in them.
#include "narrows/scene/schema.hpp"

#include "schema_tables.hpp"

namespace narrows::scene {

// Keys: {name, type, default, allowed, unit, meaning}, the cells of their rows in docs/scenes.md.
const SectionSpec &run_section() {
  static const SectionSpec section{
      "run",
      {{"engine", "string", R"(`"mpcd"`)", R"(`"mpcd"`, `"lgca"`, `"kmc"`, `"continuum"`)", "",
        "which engine runs the scene"},
       {"dimensions", "integer", "required for mpcd; 2 otherwise", "2 or 3", "",
        "dimension of the MPCD box (the lattice engines ignore it)"},
       {"seed", "integer", "42", ">= 0", "",
        "key of every random draw; the same seed gives the same run on any rank count"},
       {"steps", "integer", "required for mpcd and lgca; optional (unused) for kmc and continuum",
        ">= 0", "steps",
        "the step at which the run ends, counted from the start, so a restart continues up to it; "
        "kmc runs `kmc.time` per replica instead, continuum `continuum.time`"}}};
  return section;
}

const SectionSpec &output_section() {
  static const SectionSpec section{
      "output",
      {{"dir", "string", R"(`"out"`)", "non-empty path", "",
        "output folder (`--out` overrides it)"},
       {"every", "integer", "100", ">= 1", "steps",
        "cadence of the observables (kmc and continuum: unused; they sample `kmc.samples`, "
        "`continuum.samples` times)"},
       {"observables", "array of strings",
        R"(mpcd: `["temperature", "momentum", "velocity_profile", "density_profile"]`; lgca: `["shear_wave"]` (+ `"vacf"` with `[tagged]`, + `"colloid_vacf"`, `"colloid_diffusion"` with `[colloid]`); kmc: `["current", "density_profile"]` (+ `"shock_position"`, `"charge_profile"` when `kmc.samples > 0`); continuum: `["density", "shock_position"]` (jamming: `["density", "velocity"]`; segregation: `["density", "evolution", "steady_density"]`))",
        "the engine's observables below, each at most once", "",
        "what goes to `DIR/observables.h5`"},
       {"checkpoint_every", "integer", "0", ">= 0",
        "steps (kmc: replicas; continuum: its time steps, see `narrows check`)",
        "checkpoint cadence; 0: only at the end. A checkpoint is also written at the end and on "
        "SIGTERM/SIGUSR1"},
       {"checkpoint_keep", "integer", "2", "1 to 1000", "",
        "newest checkpoints kept in the folder"},
       {"progress", "boolean", "`true`", "", "", "progress line with ETA on long runs"},
       {"trajectory_every", "integer", "0", ">= 0; 0 with lgca, kmc and continuum", "steps",
        "write the fluid (and colloids) to `DIR/trajectory.h5` every this many steps and at the "
        "start; 0: no trajectory"},
       {"trajectory_subsample", "integer", "1", ">= 1", "",
        "frames hold the fluid particles whose id is a multiple of it"},
       {"axial_bin", "number", "2.0",
        "> 0; with `axial_fields`: at most `domain.size[0]`, which must be a whole number of "
        "bins",
        "cells", "width of the bins along x of the mpcd observable `axial_fields`"},
       {"kde_window", "integer", "0",
        ">= 0; when > 0 a multiple of `output.every`, mpcd only, needs `density_kde`", "steps",
        "windows of the colloid profiles (`density_kde`, `evolution`, "
        "`colloid_velocity_profile`): consecutive windows of this many steps from "
        "`colloids.statistics_from`, each written when it closes; 0: one average over the whole "
        "run"}}};
  return section;
}

const std::vector<const EngineSchema *> &engine_schemas() {
  // This order decides which of several sections of other engines a scene is refused for.
  static const std::vector<const EngineSchema *> engines{
      &detail::mpcd_schema(), &detail::kmc_schema(), &detail::lgca_schema(),
      &detail::continuum_schema()};
  return engines;
}

const EngineSchema &engine_schema(Engine engine) {
  for (const EngineSchema *e : engine_schemas())
    if (e->engine == engine)
      return *e;
  return *engine_schemas().front();
}

std::vector<const SectionSpec *> sections_of(Engine engine) {
  std::vector<const SectionSpec *> out{&run_section()};
  for (const auto &s : engine_schema(engine).sections)
    out.push_back(&s);
  out.push_back(&output_section());
  return out;
}

const std::vector<const SectionSpec *> &all_sections() {
  static const std::vector<const SectionSpec *> all = [] {
    std::vector<const SectionSpec *> out{&run_section()};
    for (const EngineSchema *e : engine_schemas())
      for (const auto &s : e->sections)
        out.push_back(&s);
    out.push_back(&output_section());
    return out;
  }();
  return all;
}

const SectionSpec *find_section(std::string_view name) {
  for (const SectionSpec *s : all_sections())
    if (s->name == name)
      return s;
  return nullptr;
}

Engine engine_of(std::string_view section, Engine otherwise) {
  for (const EngineSchema *e : engine_schemas())
    for (const auto &s : e->sections)
      if (s.name == section)
        return e->engine;
  return otherwise;
}

const KeySpec *find_key(const std::vector<KeySpec> &keys, std::string_view name) {
  for (const auto &k : keys)
    if (k.name == name)
      return &k;
  return nullptr;
}

} // namespace narrows::scene
