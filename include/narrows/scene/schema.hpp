// The scene schema: for each engine the sections it reads, every key of them (type, default,
// allowed values, unit, meaning) and the observables it can write. This is the one list of
// them: parse_scene reads it (which sections exist and whose they are, the keys a section
// accepts, the observables output.observables accepts and writes by default), and
// tests/unit/test_scene_docs.cpp checks docs/scenes.md against it row by row.
//
// The texts are the cells of docs/scenes.md: markdown inline text (code in backticks). The
// keys are in the order messages list them; docs/scenes.md may order its rows otherwise.
#pragma once

#include "narrows/scene/scene.hpp"

#include <string_view>
#include <vector>

namespace narrows::scene {

// One key of a section: a row `section.key` of docs/scenes.md.
struct KeySpec {
  std::string_view name; // "dt"
  std::string_view type, default_value, allowed, unit, meaning;
  // The keys of a table-valued key ([colloids.spring], [[colloids.kind]], kmc.initial), rows
  // `section.key.sub` of docs/scenes.md; empty for other keys.
  std::vector<KeySpec> sub_keys = {};
};

struct SectionSpec {
  std::string_view name; // "fluid" for [fluid]
  std::vector<KeySpec> keys;
};

// One name output.observables accepts: a row of the engine's "Observables" table.
struct ObservableSpec {
  std::string_view name, layout, meaning;
  // Whether a scene writes it when output.observables is not given (nullptr: only if listed).
  // Continuum models write exactly these: another listed observable is refused.
  bool (*by_default)(const Scene &) = nullptr;
  // An mpcd observable of the colloids: needs [colloids].
  bool follows_colloids = false;
  // Continuum: whether a scene may list it although it does not write it by default.
  bool (*on_request)(const Scene &) = nullptr;
};

struct EngineSchema {
  Engine engine;
  std::vector<SectionSpec> sections; // its own, besides [run] and [output]
  std::vector<ObservableSpec> observables;
};

// The engines, in the order a scene's sections of other engines are refused (the first found
// is named).
const std::vector<const EngineSchema *> &engine_schemas();
const EngineSchema &engine_schema(Engine engine);

// [run] and [output], read by every engine.
const SectionSpec &run_section();
const SectionSpec &output_section();

// The sections an engine reads: [run], its own, [output].
std::vector<const SectionSpec *> sections_of(Engine engine);
// Every section of every engine: [run], each engine's own in the order of engine_schemas(),
// [output]. Messages list them in this order.
const std::vector<const SectionSpec *> &all_sections();
// The section called `name`, or nullptr.
const SectionSpec *find_section(std::string_view name);
// The engine whose section `name` is (run and output: the engine given).
Engine engine_of(std::string_view section, Engine otherwise);

// The key called `name` of a section (or of a table-valued key's sub-keys), or nullptr.
const KeySpec *find_key(const std::vector<KeySpec> &keys, std::string_view name);

} // namespace narrows::scene
