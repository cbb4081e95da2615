// docs/scenes.md against the validator: every key and observable the validator accepts with an
// engine is documented under that engine, and every documented one is accepted. The accepted
// sets come from scene::accepted_keys, which is itself checked against parse_scene by probing
// (a key it lists is not refused as unknown, a section of another engine is refused).
//
// The document's convention, read here: a level-2 heading "## Engine mpcd" (lgca, kmc) opens
// an engine's part and "## All engines" the part common to all; other level-2 headings close
// them. In those parts a table row whose first cell is `section.key` documents that key (rows
// `section.key.sub` document sub-keys: their parent must be accepted), and under a level-3
// heading starting "### Observables" a row whose first cell is `name` documents an observable.
#include "narrows/core/error.hpp"
#include "narrows/scene/parse.hpp"

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

struct Documented {
  std::set<std::string> keys, sub_keys, observables;
};

// The first cell of a table row if it is one `code` span, else "".
std::string first_code_cell(const std::string &line) {
  if (line.rfind("|", 0) != 0)
    return {};
  const auto end = line.find('|', 1);
  std::string cell = line.substr(1, end == std::string::npos ? std::string::npos : end - 1);
  cell.erase(0, cell.find_first_not_of(' '));
  cell.erase(cell.find_last_not_of(' ') + 1);
  if (cell.size() < 3 || cell.front() != '`' || cell.back() != '`')
    return {};
  cell = cell.substr(1, cell.size() - 2);
  return cell.find('`') == std::string::npos ? cell : std::string();
}

std::map<Engine, Documented> read_docs(const std::string &path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot open " << path;
  std::map<Engine, Documented> out;
  std::vector<Engine> scope;
  bool observables = false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      observables = false;
      scope.clear();
      if (line == "## All engines")
        scope = engines;
      else if (line == "## Engine mpcd")
        scope = {Engine::mpcd};
      else if (line == "## Engine lgca")
        scope = {Engine::lgca};
      else if (line == "## Engine kmc")
        scope = {Engine::kmc};
      else if (line == "## Engine continuum")
        scope = {Engine::continuum};
      continue;
    }
    if (line.rfind("### ", 0) == 0) {
      observables = line.rfind("### Observables", 0) == 0;
      continue;
    }
    const std::string name = first_code_cell(line);
    if (name.empty())
      continue;
    for (Engine e : scope) {
      if (observables)
        out[e].observables.insert(name);
      else if (std::count(name.begin(), name.end(), '.') == 1)
        out[e].keys.insert(name);
      else
        out[e].sub_keys.insert(name);
    }
  }
  return out;
}

std::string listed(const std::set<std::string> &names) {
  std::string s;
  for (const auto &n : names)
    s += (s.empty() ? "" : ", ") + n;
  return s;
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

// accepted_keys lists what parse_scene accepts: each listed key is known (not "unknown key"),
// a key not listed is unknown, and a section of another engine is refused as such.
TEST(SceneDocs, AcceptedKeysAreThoseOfTheValidator) {
  std::set<std::string> all_sections;
  for (Engine e : engines)
    for (const auto &k : accepted_keys(e).keys)
      all_sections.insert(k.substr(0, k.find('.')));
  for (Engine e : engines) {
    const AcceptedKeys acc = accepted_keys(e);
    std::set<std::string> sections;
    for (const auto &k : acc.keys) {
      const std::string sec = k.substr(0, k.find('.')), key = k.substr(k.find('.') + 1);
      sections.insert(sec);
      Table t = minimal(e);
      t[sec][key] = "\"probe\"";
      const std::string msg = refusal(t);
      EXPECT_EQ(msg.find("unknown key"), std::string::npos)
          << to_string(e) << " " << k << ": " << msg;
      EXPECT_EQ(msg.find("is for engine"), std::string::npos)
          << to_string(e) << " " << k << ": " << msg;
      EXPECT_EQ(msg.find("needs run.engine"), std::string::npos)
          << to_string(e) << " " << k << ": " << msg;
    }
    for (const auto &sec : sections) {
      Table t = minimal(e);
      t[sec]["not_a_key"] = "1";
      EXPECT_NE(refusal(t).find("unknown key '" + sec + ".not_a_key'"), std::string::npos)
          << to_string(e) << " [" << sec << "]: " << refusal(t);
    }
    for (const auto &sec : all_sections) {
      if (sections.count(sec))
        continue;
      Table t = minimal(e);
      t[sec];
      const std::string msg = refusal(t);
      EXPECT_TRUE(msg.find("is for engine") != std::string::npos ||
                  msg.find("needs run.engine") != std::string::npos)
          << to_string(e) << " accepts [" << sec << "], not in accepted_keys: " << msg;
    }
    for (const auto &name : acc.observables) {
      Table t = minimal(e);
      t["output"]["observables"] = "[\"" + name + "\"]";
      EXPECT_EQ(refusal(t).find("is not a known observable"), std::string::npos)
          << to_string(e) << " " << name << ": " << refusal(t);
    }
    Table t = minimal(e);
    t["output"]["observables"] = "[\"not_an_observable\"]";
    EXPECT_NE(refusal(t).find("is not a known observable"), std::string::npos) << refusal(t);
  }
}

TEST(SceneDocs, EveryAcceptedKeyIsDocumentedAndEveryDocumentedKeyIsAccepted) {
  const std::string path = std::string(NARROWS_SOURCE_DIR) + "/docs/scenes.md";
  const auto docs = read_docs(path);
  for (Engine e : engines) {
    const AcceptedKeys acc = accepted_keys(e);
    const std::set<std::string> keys(acc.keys.begin(), acc.keys.end());
    const std::set<std::string> obs(acc.observables.begin(), acc.observables.end());
    const Documented d = docs.count(e) ? docs.at(e) : Documented{};
    std::set<std::string> undocumented, unknown, undocumented_obs, unknown_obs, orphans;
    std::set_difference(keys.begin(), keys.end(), d.keys.begin(), d.keys.end(),
                        std::inserter(undocumented, undocumented.end()));
    std::set_difference(d.keys.begin(), d.keys.end(), keys.begin(), keys.end(),
                        std::inserter(unknown, unknown.end()));
    std::set_difference(obs.begin(), obs.end(), d.observables.begin(), d.observables.end(),
                        std::inserter(undocumented_obs, undocumented_obs.end()));
    std::set_difference(d.observables.begin(), d.observables.end(), obs.begin(), obs.end(),
                        std::inserter(unknown_obs, unknown_obs.end()));
    for (const auto &sub : d.sub_keys) {
      const auto second = sub.find('.', sub.find('.') + 1);
      if (!keys.count(sub.substr(0, second)))
        orphans.insert(sub);
    }
    EXPECT_TRUE(undocumented.empty()) << "accepted by the validator with engine " << to_string(e)
                                      << " but not in " << path << ": " << listed(undocumented);
    EXPECT_TRUE(unknown.empty()) << "documented in " << path << " for engine " << to_string(e)
                                 << " but not accepted: " << listed(unknown);
    EXPECT_TRUE(undocumented_obs.empty()) << "observables accepted with engine " << to_string(e)
                                          << " but not documented: " << listed(undocumented_obs);
    EXPECT_TRUE(unknown_obs.empty()) << "observables documented for engine " << to_string(e)
                                     << " but not accepted: " << listed(unknown_obs);
    EXPECT_TRUE(orphans.empty()) << "sub-keys documented for engine " << to_string(e)
                                 << " whose key is not accepted: " << listed(orphans);
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
