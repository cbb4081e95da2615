// Reading a scene: TOML text -> validated scene::Scene. The order of the checks: the TOML text,
// the overrides, [run] (the engine decides which sections exist), names the schema does not know,
// sections of other engines, the engine's own sections, [output] and the observables.
//
// Every problem becomes one narrows::input_error line of the form
//   <source>: <key> ... found ...; allowed: ...
// where <source> is the scene file, or "--set '<override>'" when the offending value came from the
// command line.
#include "narrows/scene/parse.hpp"

#include "canonical_toml.hpp"
#include "checker.hpp"
#include "narrows/scene/schema.hpp"
#include "overrides.hpp"
#include "parse_common.hpp"
#include "parse_continuum.hpp"
#include "parse_kmc.hpp"
#include "parse_lgca.hpp"
#include "parse_mpcd.hpp"
#include "toml_errors.hpp"
#include "unknown_names.hpp"

#include <string>
#include <vector>

namespace narrows::scene {

namespace {

using detail::Checker;
using toml::value;

// Refuses a section of another engine than `engine`: the first one, engine by engine.
void refuse_other_engines(const Checker &c, const value &root, Engine engine) {
  std::string allowed;
  for (const SectionSpec *sec : sections_of(engine))
    allowed += (allowed.empty() ? "[" : ", [") + std::string(sec->name) + "]";
  for (const EngineSchema *other : engine_schemas()) {
    if (other->engine == engine)
      continue;
    for (const auto &sec : other->sections) {
      const std::string name(sec.name);
      if (c.section(root, name.c_str()) == nullptr)
        continue;
      // mpcd is the engine of a scene without run.engine: the likely mistake is a missing one.
      if (engine == Engine::mpcd)
        c.fail(name, "section [" + name + "] needs run.engine = \"" + to_string(other->engine) +
                         "\"; allowed with run.engine = \"" + to_string(engine) + "\": " + allowed);
      c.fail(name, "section [" + name + "] is for engine " + to_string(other->engine) +
                       "; allowed with run.engine = \"" + to_string(engine) + "\": " + allowed);
    }
  }
}

// The observables the scene writes when output.observables is not given.
std::vector<std::string> default_observables(const Scene &s) {
  std::vector<std::string> out;
  for (const auto &o : engine_schema(s.run.engine).observables)
    if (o.by_default != nullptr && o.by_default(s))
      out.emplace_back(o.name);
  return out;
}

} // namespace

Scene parse_scene(const std::string &text, const std::string &file,
                  const std::vector<std::string> &overrides) {
  Checker c(file);
  value root = detail::parse_toml(text, file);

  Scene s;
  s.file = file;
  s.text = text;
  for (const auto &o : overrides)
    detail::apply_override(c, root, o);
  if (!overrides.empty()) {
    // Output files store the scene that ran: the overridden table, re-serialised (the
    // file's comments are lost), headed by where it came from.
    s.text = "# " + detail::one_line(file) + " with overrides:\n";
    for (const auto &o : overrides)
      s.text += "# --set " + detail::one_line(o) + "\n";
    s.text += toml::format(root);
  }
  s.canonical = detail::canonical_text(root);

  // The engine decides which sections exist, so it is checked first.
  const value *run = c.section(root, "run");
  s.run.engine = detail::parse_engine(c, run);
  for (const auto &[name, v] : detail::in_file_order(root))
    if (find_section(name) == nullptr)
      c.fail(name, detail::unknown_section_message(name, *v));
  detail::parse_run(c, run, s.run);
  refuse_other_engines(c, root, s.run.engine);

  switch (s.run.engine) {
  case Engine::mpcd:
    detail::parse_mpcd(c, root, s);
    break;
  case Engine::lgca:
    detail::parse_lgca_scene(c, root, s);
    break;
  case Engine::kmc:
    detail::parse_kmc_scene(c, root, s);
    break;
  case Engine::continuum:
    detail::parse_continuum_scene(c, root, s);
    break;
  }
  s.output.observables = default_observables(s);
  detail::parse_output(c, c.section(root, "output"), s.run.engine, s.output);
  if (s.run.engine == Engine::mpcd)
    detail::check_mpcd_observables(c, s);
  if (s.run.engine == Engine::continuum)
    detail::check_continuum_observables(c, s);
  return s;
}

} // namespace narrows::scene
