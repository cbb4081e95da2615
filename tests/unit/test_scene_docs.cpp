// docs/scenes.md against the scene schema (scene/schema.hpp), and the schema against the
// validator. Every key of every section an engine reads is documented under that engine by a
// row whose cells (type, default, allowed, unit, meaning) are the schema's, and every documented
// key is the schema's; likewise the observables (layout, meaning) and the table of each engine's
// sections. The validator accepts exactly the schema's sections and keys with each engine
// (probed through parse_scene).
//
// The document's convention, read here: a level-2 heading "## Engine mpcd" (lgca, kmc,
// continuum) opens an engine's part and "## All engines" the part common to all; other level-2
// headings close them. In those parts a table row whose first cell is `section.key` documents
// that key (`section.key.sub` a sub-key of a table-valued key), and under a level-3 heading
// starting "### Observables" a row whose first cell is `name` documents an observable. Before the
// first level-2 heading, the rows `engine` (or `engine` (default)) | `[section]`, ... list the
// sections of each engine.
#include "narrows/core/error.hpp"
#include "narrows/scene/parse.hpp"
#include "narrows/scene/schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::scene;

const std::vector<Engine> engines{Engine::mpcd, Engine::lgca, Engine::kmc, Engine::continuum};

// The cells of a table row, trimmed, "\|" read as "|" ({} if the line is no table row).
std::vector<std::string> cells_of(const std::string &line) {
  if (line.rfind("|", 0) != 0)
    return {};
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      out.push_back(cell);
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return out;
}

// The name in a first cell that is one `code` span, else "".
std::string code_name(const std::string &cell) {
  if (cell.size() < 3 || cell.front() != '`' || cell.back() != '`')
    return {};
  const std::string name = cell.substr(1, cell.size() - 2);
  return name.find('`') == std::string::npos ? name : std::string();
}

// A documented row: its cells after the first, and its line in the file.
struct Row {
  std::vector<std::string> cells;
  int line = 0;
};

struct Documented {
  std::map<std::string, Row> keys, observables; // "section.key" or "section.key.sub"; name
  std::string sections;                         // the cell of the engine's sections table
};

std::map<Engine, Documented> read_docs(const std::string &path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot open " << path;
  std::map<Engine, Documented> out;
  std::vector<Engine> scope;
  bool preamble = true, observables = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("## ", 0) == 0) {
      preamble = false;
      observables = false;
      scope.clear();
      if (line == "## All engines")
        scope = engines;
      for (Engine e : engines)
        if (line == std::string("## Engine ") + to_string(e))
          scope = {e};
      continue;
    }
    if (line.rfind("### ", 0) == 0) {
      observables = line.rfind("### Observables", 0) == 0;
      continue;
    }
    const auto cells = cells_of(line);
    if (cells.size() < 2)
      continue;
    if (preamble) { // `engine` (default) | `[section]`, ...
      for (Engine e : engines) {
        const std::string name = std::string("`") + to_string(e) + "`";
        if (cells[0] == name || cells[0] == name + " (default)")
          out[e].sections = cells[1];
      }
      continue;
    }
    const std::string name = code_name(cells[0]);
    if (name.empty())
      continue;
    const Row row{std::vector<std::string>(cells.begin() + 1, cells.end()), number};
    for (Engine e : scope)
      (observables ? out[e].observables : out[e].keys)[name] = row;
  }
  return out;
}

// What the schema says of each key of an engine ("section.key" and "section.key.sub").
std::map<std::string, std::vector<std::string>> schema_keys(Engine e) {
  std::map<std::string, std::vector<std::string>> out;
  const auto add = [&out](const std::string &prefix, const KeySpec &k, const auto &self) -> void {
    const std::string name = prefix + std::string(k.name);
    out[name] = {std::string(k.type), std::string(k.default_value), std::string(k.allowed),
                 std::string(k.unit), std::string(k.meaning)};
    for (const auto &sub : k.sub_keys)
      self(name + ".", sub, self);
  };
  for (const SectionSpec *sec : sections_of(e))
    for (const auto &k : sec->keys)
      add(std::string(sec->name) + ".", k, add);
  return out;
}

std::map<std::string, std::vector<std::string>> schema_observables(Engine e) {
  std::map<std::string, std::vector<std::string>> out;
  for (const auto &o : engine_schema(e).observables)
    out[std::string(o.name)] = {std::string(o.layout), std::string(o.meaning)};
  return out;
}

// The markdown row the schema asks for (cells joined, "|" escaped), for the failure message.
std::string row_text(const std::string &name, const std::vector<std::string> &cells) {
  std::string s = "| `" + name + "` |";
  for (const auto &cell : cells) {
    std::string escaped;
    for (const char ch : cell)
      escaped += ch == '|' ? std::string("\\|") : std::string(1, ch);
    s += escaped.empty() ? " |" : " " + escaped + " |";
  }
  return s;
}

// Compares documented rows with the schema's: missing, extra and differing rows.
void compare(const std::string &path, Engine e, const std::string &what,
             const std::map<std::string, Row> &documented,
             const std::map<std::string, std::vector<std::string>> &schema) {
  for (const auto &[name, cells] : schema) {
    const auto it = documented.find(name);
    if (it == documented.end())
      ADD_FAILURE() << "the schema's " << what << " of engine " << to_string(e) << " '" << name
                    << "' has no row in " << path << "; add:\n"
                    << row_text(name, cells);
    else if (it->second.cells != cells)
      ADD_FAILURE() << path << ":" << it->second.line << ": the row of " << what << " '" << name
                    << "' (engine " << to_string(e) << ") is not the schema's (scene/schema_"
                    << to_string(e) << ".cpp or scene/schema.cpp); the schema says:\n"
                    << row_text(name, cells);
  }
  for (const auto &[name, row] : documented)
    if (!schema.count(name))
      ADD_FAILURE() << path << ":" << row.line << ": " << what << " '" << name
                    << "' is documented for engine " << to_string(e) << " but is not in its schema";
}

TEST(SceneDocs, EveryRowIsTheSchemas) {
  const std::string path = std::string(NARROWS_SOURCE_DIR) + "/docs/scenes.md";
  const auto docs = read_docs(path);
  for (Engine e : engines) {
    const Documented d = docs.count(e) ? docs.at(e) : Documented{};
    compare(path, e, "key", d.keys, schema_keys(e));
    compare(path, e, "observable", d.observables, schema_observables(e));
    std::string sections;
    for (const SectionSpec *sec : sections_of(e))
      sections += (sections.empty() ? "`[" : ", `[") + std::string(sec->name) + "]`";
    EXPECT_EQ(d.sections, sections) << "the sections of engine " << to_string(e) << " in " << path;
  }
}

// A minimal valid scene of each engine, as section -> key -> TOML value.
using Table = std::map<std::string, std::map<std::string, std::string>>;

Table minimal(Engine e) {
  if (e == Engine::kmc)
    return {{"run", {{"engine", "\"kmc\""}}},
            {"kmc",
             {{"length", "10"},
              {"rates", "{ \"10->01\" = 1.0 }"},
              {"initial", "{ kind = \"product\", probabilities = [0.5, 0.5, 0.0] }"},
              {"time", "1.0"}}}};
  if (e == Engine::continuum)
    return {{"run", {{"engine", "\"continuum\""}}},
            {"continuum",
             {{"model", "\"conservation-law\""},
              {"flux", "\"burgers\""},
              {"length", "10.0"},
              {"cells", "10"},
              {"initial", "{ kind = \"riemann\", left = 1.0, right = 0.0 }"},
              {"time", "1.0"}}}};
  if (e == Engine::lgca)
    return {{"run", {{"engine", "\"lgca\""}, {"steps", "1"}}},
            {"lattice", {{"model", "\"fhp-i\""}, {"size", "[8, 8]"}, {"density", "0.2"}}}};
  return {{"run", {{"dimensions", "2"}, {"steps", "1"}}},
          {"domain", {{"size", "[8, 8]"}}},
          {"fluid", {{"collision", "\"srd\""}, {"dt", "0.1"}}}};
}

std::string text(const Table &t) {
  std::string s;
  for (const auto &[sec, keys] : t) {
    s += "[" + sec + "]\n";
    for (const auto &[k, v] : keys)
      s += k + " = " + v + "\n";
  }
  return s;
}

// parse_scene's message, or "" if the scene is accepted.
std::string refusal(const Table &t) {
  try {
    parse_scene(text(t), "probe.toml");
  } catch (const Error &e) {
    return e.what();
  }
  return {};
}

TEST(SceneDocs, MinimalScenesAreAccepted) {
  for (Engine e : engines)
    EXPECT_EQ(refusal(minimal(e)), "") << to_string(e);
}

// The validator reads the schema: each key of an engine's sections is known (not "unknown
// key"), a key not listed is unknown, a section of another engine is refused as such, and
// output.observables takes exactly the engine's observables.
TEST(SceneDocs, TheValidatorAcceptsTheSchema) {
  for (Engine e : engines) {
    std::set<std::string> mine;
    for (const SectionSpec *sec : sections_of(e)) {
      mine.insert(std::string(sec->name));
      for (const auto &key : sec->keys) {
        const std::string k = std::string(sec->name) + "." + std::string(key.name);
        Table t = minimal(e);
        t[std::string(sec->name)][std::string(key.name)] = "\"probe\"";
        const std::string msg = refusal(t);
        EXPECT_EQ(msg.find("unknown key"), std::string::npos)
            << to_string(e) << " " << k << ": " << msg;
        EXPECT_EQ(msg.find("is for engine"), std::string::npos)
            << to_string(e) << " " << k << ": " << msg;
        EXPECT_EQ(msg.find("needs run.engine"), std::string::npos)
            << to_string(e) << " " << k << ": " << msg;
      }
      Table t = minimal(e);
      t[std::string(sec->name)]["not_a_key"] = "1";
      EXPECT_NE(refusal(t).find("unknown key '" + std::string(sec->name) + ".not_a_key'"),
                std::string::npos)
          << to_string(e) << " [" << sec->name << "]: " << refusal(t);
    }
    for (const SectionSpec *sec : all_sections()) {
      if (mine.count(std::string(sec->name)))
        continue;
      Table t = minimal(e);
      t[std::string(sec->name)];
      const std::string msg = refusal(t);
      EXPECT_TRUE(msg.find("is for engine") != std::string::npos ||
                  msg.find("needs run.engine") != std::string::npos)
          << to_string(e) << " accepts [" << sec->name << "] of another engine: " << msg;
    }
    Table t = minimal(e);
    t["unknown_section"];
    EXPECT_NE(refusal(t).find("unknown section [unknown_section]"), std::string::npos)
        << refusal(t);
    for (const auto &o : engine_schema(e).observables) {
      Table t = minimal(e);
      t["output"]["observables"] = "[\"" + std::string(o.name) + "\"]";
      EXPECT_EQ(refusal(t).find("is not a known observable"), std::string::npos)
          << to_string(e) << " " << o.name << ": " << refusal(t);
    }
    t = minimal(e);
    t["output"]["observables"] = "[\"not_an_observable\"]";
    EXPECT_NE(refusal(t).find("is not a known observable"), std::string::npos) << refusal(t);
  }
}

// kmc and continuum have no run.steps (they run kmc.time per replica, continuum.time): run.steps
// is optional there, still accepted, and required by the stepping engines.
TEST(SceneDocs, RunStepsIsOptionalForKmcAndContinuumOnly) {
  for (Engine e : {Engine::kmc, Engine::continuum}) {
    Table t = minimal(e);
    EXPECT_EQ(refusal(t), "") << to_string(e);
    t["run"]["steps"] = "5";
    EXPECT_EQ(refusal(t), "") << to_string(e);
  }
  for (Engine e : {Engine::mpcd, Engine::lgca}) {
    Table t = minimal(e);
    t["run"].erase("steps");
    EXPECT_NE(refusal(t).find("missing required key 'run.steps'"), std::string::npos)
        << to_string(e) << ": " << refusal(t);
  }
}

} // namespace
