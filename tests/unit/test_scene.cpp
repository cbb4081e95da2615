// Scene reader: good scenes, defaults, --set overrides, and one-line errors for bad scenes.
#include "narrows/core/error.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace narrows;
using namespace narrows::scene;

const std::string good_scene = R"(
[run]
engine = "mpcd"
dimensions = 2
seed = 7
steps = 20000

[domain]
size = [200.0, 20]

[fluid]
collision = "srd"
density = 5
dt = 0.1
angle = 130.0
kT = 1.0

[body_force]
value = [0.001, 0.0]

[output]
dir = "results"
every = 50
observables = ["temperature", "velocity_profile"]
checkpoint_every = 1000
progress = false
)";

const std::string minimal_scene = R"(
[run]
dimensions = 3
steps = 10

[domain]
size = [8, 8, 8]

[fluid]
collision = "at+a"
dt = 0.05
)";

// Parses `text` as file "bad.toml" and returns the error message; fails the test unless a
// narrows::Error with ExitCode::bad_input is thrown whose message is one line naming the file
// and every string in `must_contain`.
std::string bad(const std::string &text, const std::vector<std::string> &must_contain,
                const std::vector<std::string> &overrides = {},
                const std::string &file = "run/bad.toml") {
  try {
    parse_scene(text, file, overrides);
  } catch (const Error &e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.code(), ExitCode::bad_input) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\r'), std::string::npos) << msg;
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    for (const auto &s : must_contain)
      EXPECT_NE(msg.find(s), std::string::npos) << "missing '" << s << "' in: " << msg;
    return msg;
  } catch (const std::exception &e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

// The minimal scene with one line replaced (matched by its key) or appended.
std::string with(const std::string &section, const std::string &line,
                 const std::string &base = minimal_scene) {
  const std::string header = "[" + section + "]\n";
  std::string text = base;
  const auto at = text.find(header);
  if (at == std::string::npos)
    return text + "\n" + header + line + "\n";
  const auto key = line.substr(0, line.find(' '));
  const auto body = at + header.size();
  const auto end = text.find("\n[", body);
  const auto found = text.find("\n" + key + " ", body - 1);
  if (found != std::string::npos && (end == std::string::npos || found < end)) {
    const auto eol = text.find('\n', found + 1);
    text.replace(found + 1, eol - found - 1, line);
  } else {
    text.insert(body, line + "\n");
  }
  return text;
}

// ---- good scenes --------------------------------------------------------------------------------

TEST(Scene, GoodSceneParsesWithItsValues) {
  const Scene s = parse_scene(good_scene, "run/good.toml");
  EXPECT_EQ(s.file, "run/good.toml");
  EXPECT_EQ(s.text, good_scene);
  EXPECT_EQ(s.run.engine, Engine::mpcd);
  EXPECT_EQ(s.run.dimensions, 2);
  EXPECT_EQ(s.run.seed, 7u);
  EXPECT_EQ(s.run.steps, 20000);
  EXPECT_DOUBLE_EQ(s.domain.size[0], 200.0);
  EXPECT_DOUBLE_EQ(s.domain.size[1], 20.0);
  EXPECT_DOUBLE_EQ(s.domain.size[2], 0.0);
  EXPECT_EQ(s.fluid.collision, Collision::srd);
  EXPECT_DOUBLE_EQ(s.fluid.density, 5.0);
  EXPECT_DOUBLE_EQ(s.fluid.dt, 0.1);
  EXPECT_DOUBLE_EQ(s.fluid.angle_deg, 130.0);
  EXPECT_DOUBLE_EQ(s.fluid.kT, 1.0);
  EXPECT_EQ(s.fluid.sort_every, 20);
  ASSERT_TRUE(s.body_force.has_value());
  EXPECT_EQ(s.body_force->kind, ForceKind::constant);
  EXPECT_DOUBLE_EQ(s.body_force->value[0], 0.001);
  EXPECT_DOUBLE_EQ(s.body_force->value[1], 0.0);
  EXPECT_EQ(s.output.dir, "results");
  EXPECT_EQ(s.output.every, 50);
  EXPECT_EQ(s.output.observables, (std::vector<std::string>{"temperature", "velocity_profile"}));
  EXPECT_EQ(s.output.checkpoint_every, 1000);
  EXPECT_FALSE(s.output.progress);
}

TEST(Scene, DefaultsFillOptionalKeys) {
  const Scene s = parse_scene(minimal_scene, "min.toml");
  EXPECT_EQ(s.run.engine, Engine::mpcd);
  EXPECT_EQ(s.run.dimensions, 3);
  EXPECT_EQ(s.run.seed, 42u);
  EXPECT_EQ(s.run.steps, 10);
  EXPECT_DOUBLE_EQ(s.domain.size[2], 8.0);
  EXPECT_EQ(s.fluid.collision, Collision::at_a);
  EXPECT_DOUBLE_EQ(s.fluid.density, 10.0);
  EXPECT_DOUBLE_EQ(s.fluid.dt, 0.05);
  EXPECT_DOUBLE_EQ(s.fluid.angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(s.fluid.kT, 1.0);
  EXPECT_EQ(s.fluid.sort_every, 20);
  EXPECT_FALSE(s.body_force.has_value());
  EXPECT_EQ(s.output.dir, "out");
  EXPECT_EQ(s.output.every, 100);
  EXPECT_EQ(s.output.observables.size(), 4u);
  EXPECT_EQ(s.output.checkpoint_every, 0);
  EXPECT_TRUE(s.output.progress);
}

TEST(Scene, SineBodyForce) {
  const Scene s = parse_scene(minimal_scene + "\n[body_force]\nkind = \"sine\"\namplitude = 0.01\n",
                              "sine.toml");
  ASSERT_TRUE(s.body_force.has_value());
  EXPECT_EQ(s.body_force->kind, ForceKind::sine);
  EXPECT_DOUBLE_EQ(s.body_force->amplitude, 0.01);
}

TEST(Scene, AllCollisionRulesAndNames) {
  for (const Collision c : {Collision::srd, Collision::at, Collision::at_a,
                            Collision::random_permute, Collision::random_maxwell}) {
    const Scene s =
        parse_scene(minimal_scene, "c.toml", {std::string("fluid.collision=") + to_string(c)});
    EXPECT_EQ(s.fluid.collision, c) << to_string(c);
  }
  EXPECT_STREQ(to_string(Engine::mpcd), "mpcd");
  EXPECT_STREQ(to_string(Engine::continuum), "continuum");
}

TEST(Scene, LoadSceneReadsAFile) {
  const auto path = std::filesystem::temp_directory_path() / "narrows_test_scene_load.toml";
  {
    std::ofstream out(path);
    out << good_scene;
  }
  const Scene s = load_scene(path.string());
  const Scene o = load_scene(path.string(), {"run.steps=5"});
  std::filesystem::remove(path);
  EXPECT_EQ(s.file, path.string());
  EXPECT_EQ(s.text, good_scene);
  EXPECT_EQ(o.run.steps, 5);
}

// ---- overrides ----------------------------------------------------------------------------------

TEST(SceneOverrides, NumberArrayBareWordAndBool) {
  const Scene s =
      parse_scene(good_scene, "run/good.toml",
                  {"fluid.dt=0.05", "run.steps=2000", "domain.size=[32.0,64.0]",
                   "fluid.collision=at+a", "output.progress=true", "fluid.density = 3"});
  EXPECT_DOUBLE_EQ(s.fluid.dt, 0.05);
  EXPECT_EQ(s.run.steps, 2000);
  EXPECT_DOUBLE_EQ(s.domain.size[0], 32.0);
  EXPECT_DOUBLE_EQ(s.domain.size[1], 64.0);
  EXPECT_EQ(s.fluid.collision, Collision::at_a);
  EXPECT_TRUE(s.output.progress);
  EXPECT_DOUBLE_EQ(s.fluid.density, 3.0);
}

TEST(SceneOverrides, QuotedStringAndNewSection) {
  const Scene s = parse_scene(minimal_scene, "min.toml",
                              {"output.dir=\"sweep/a b\"", "body_force.kind=sine",
                               "body_force.amplitude=0.02", "output.observables=[\"momentum\"]"});
  EXPECT_EQ(s.output.dir, "sweep/a b");
  ASSERT_TRUE(s.body_force.has_value());
  EXPECT_EQ(s.body_force->kind, ForceKind::sine);
  EXPECT_DOUBLE_EQ(s.body_force->amplitude, 0.02);
  EXPECT_EQ(s.output.observables, std::vector<std::string>{"momentum"});
}

TEST(SceneOverrides, LaterOverrideWins) {
  const Scene s = parse_scene(minimal_scene, "min.toml", {"run.seed=1", "run.seed=2"});
  EXPECT_EQ(s.run.seed, 2u);
}

TEST(SceneOverrides, TextIsTheSceneThatRuns) {
  // The stored text is the overridden scene: parsing it again gives the same values.
  const Scene s = parse_scene(minimal_scene, "min.toml", {"fluid.dt=0.05", "run.steps=7"});
  EXPECT_NE(s.text.find("# --set fluid.dt=0.05\n# --set run.steps=7\n"), std::string::npos);
  const Scene again = parse_scene(s.text, "stored");
  EXPECT_EQ(again.fluid.dt, 0.05);
  EXPECT_EQ(again.run.steps, 7);
  EXPECT_EQ(again.fluid.density, s.fluid.density);
  // Without overrides the file's own text (with its comments) is kept.
  EXPECT_EQ(parse_scene(minimal_scene, "min.toml").text, minimal_scene);
}

// ---- bad scenes ---------------------------------------------------------------------------------

TEST(SceneErrors, UnknownKeyWithHint) {
  const auto msg = bad(with("fluid", "desnity = 3"), {"fluid.desnity", "allowed keys in [fluid]"});
  EXPECT_NE(msg.find("did you mean 'fluid.density'"), std::string::npos) << msg;
}

TEST(SceneErrors, UnknownSection) { bad(minimal_scene + "\n[fluidd]\ndt = 1\n", {"fluidd"}); }

TEST(SceneErrors, WrongTypeNamesTheTomlType) {
  bad(with("fluid", "dt = \"fast\""), {"fluid.dt", "\"fast\"", "(string)"});
  bad(with("output", "progress = 1"), {"output.progress", "(integer)"});
}

TEST(SceneErrors, FloatWhereIntegerExpected) {
  bad(with("run", "steps = 2.5"), {"run.steps", "found 2.5 (float)", "allowed: an integer"});
}

TEST(SceneErrors, NegativeDensity) {
  bad(with("fluid", "density = -1.0"), {"fluid.density = -1.0", "out of range", "> 0"});
}

TEST(SceneErrors, TooManyParticles) {
  bad(with("fluid", "density = 1e9", with("domain", "size = [1000, 1000, 1000]")),
      {"fluid.density", "2^40"});
}

TEST(SceneErrors, AngleOutOfRange) {
  bad(with("fluid", "angle = 400.0"), {"fluid.angle = 400.0", "0 < angle < 360"});
  bad(with("fluid", "angle = 0"), {"fluid.angle = 0", "0 < angle < 360"});
}

TEST(SceneErrors, DtNotPositive) {
  bad(with("fluid", "dt = 0"), {"fluid.dt = 0", "> 0"});
  bad(with("fluid", "dt = -0.1"), {"fluid.dt = -0.1", "> 0"});
  bad(with("fluid", "dt = nan"), {"fluid.dt = nan"});
}

TEST(SceneErrors, DimensionsFour) { bad(with("run", "dimensions = 4"), {"run.dimensions = 4"}); }

TEST(SceneErrors, SizeOfWrongLength) {
  bad(with("domain", "size = [8, 8]"), {"domain.size", "2 entries", "3 entries"});
}

TEST(SceneErrors, NonIntegerSize) {
  bad(with("domain", "size = [8, 8.5, 8]"), {"domain.size[1] = 8.5", "whole number"});
  bad(with("domain", "size = [8, 1, 8]"), {"domain.size[1] = 1", "out of range"});
  bad(with("domain", "size = [8, 8, \"8\"]"), {"domain.size[2]", "(string)"});
}

TEST(SceneErrors, UnknownCollisionRule) {
  const auto msg =
      bad(with("fluid", "collision = \"srdd\""), {"fluid.collision = \"srdd\"", "random-maxwell"});
  EXPECT_NE(msg.find("did you mean \"srd\""), std::string::npos) << msg;
}

TEST(SceneErrors, MissingFluidSection) {
  bad("[run]\ndimensions = 2\nsteps = 1\n[domain]\nsize = [4, 4]\n", {"[fluid]", "missing"});
}

TEST(SceneErrors, MissingSteps) {
  bad("[run]\ndimensions = 2\n[domain]\nsize = [4, 4]\n[fluid]\ncollision = \"srd\"\ndt = 1\n",
      {"run.steps", "missing"});
}

TEST(SceneErrors, NonExistentFile) {
  const std::string path = "no/such/dir/scene.toml";
  try {
    load_scene(path);
    FAIL() << "no error";
  } catch (const Error &e) {
    EXPECT_EQ(e.code(), ExitCode::bad_input);
    EXPECT_EQ(std::string(e.what()), path + ": cannot open scene file (No such file or directory)");
  }
}

TEST(SceneErrors, TomlSyntaxErrorCarriesLineNumber) {
  const auto msg = bad("[run]\ndimensions = 2\nsteps = 10\n[fluid]\ndt = = 3\n", {"line 5"});
  EXPECT_NE(msg.find("syntax"), std::string::npos) << msg;
  bad("[run]\nsteps = 1\nsteps = 2\n", {"line 3", "steps"});
  bad("[run]\nsize = [1,\n2\n", {"line "});
}

TEST(SceneErrors, BadSetPath) {
  bad(minimal_scene, {"--set 'xyz': expected key.path=value"}, {"xyz"});
  bad(minimal_scene, {"--set 'fluid.dt': expected key.path=value"}, {"fluid.dt"});
  bad(minimal_scene, {"--set 'steps=3': expected key.path=value"}, {"steps=3"});
  bad(minimal_scene, {"--set 'fluid..dt=3'"}, {"fluid..dt=3"});
}

TEST(SceneErrors, UnknownSetKeyNamesSet) {
  const auto msg = bad(minimal_scene, {"--set 'fluid.desnity=3'", "unknown key 'fluid.desnity'"},
                       {"fluid.desnity=3"});
  EXPECT_EQ(msg.rfind("--set", 0), 0u) << msg;
  bad(minimal_scene, {"--set 'fluidd.dt=3'", "fluidd.dt"}, {"fluidd.dt=3"});
  bad(minimal_scene, {"--set 'fluid.dt.x=3'", "fluid.dt.x"}, {"fluid.dt.x=3"});
}

TEST(SceneErrors, BadSetValueNamesSet) {
  const auto msg =
      bad(minimal_scene, {"--set 'fluid.angle=400'", "fluid.angle = 400"}, {"fluid.angle=400"});
  EXPECT_EQ(msg.rfind("--set", 0), 0u) << msg;
  bad(minimal_scene, {"--set 'domain.size=[8,8]'", "domain.size"}, {"domain.size=[8,8]"});
}

TEST(SceneErrors, UnknownEngineAndSectionsOfAnotherEngine) {
  bad(with("run", "engine = \"continuum\""),
      {"section [domain] is for engine mpcd", "[run], [continuum], [output]"});
  bad(with("run", "engine = \"lbm\""), {"run.engine = \"lbm\"", "mpcd", "continuum"});
}

TEST(SceneErrors, WallsKeys) {
  bad(minimal_scene + "\n[walls]\nslip = 1\n", {"walls.slip", "found 1", "true or false"});
  bad(minimal_scene + "\n[walls]\nvirtual = true\n", {"walls.virtual", "virtual_particles"});
  bad(minimal_scene, {"walls.slipp", "walls.slip"}, {"walls.slipp=true"});
  bad(minimal_scene + "\n[body_force]\nkind = \"sine\"\namplitude = 0.1\n[walls]\n",
      {"[walls]", "sine"});
  bad(minimal_scene + "\n[walls]\nvirtual_flow = \"mirrored\"\n",
      {"walls.virtual_flow", "mirrored", "mirror"});
  bad(minimal_scene + "\n[walls]\nslip = true\nvirtual_flow = \"mirror\"\n",
      {"walls.virtual_flow", "slip"});
}

TEST(Scene, WallsDefaultsAndOverrides) {
  const Scene s = parse_scene(minimal_scene + "\n[walls]\n", "w.toml", {"walls.slip=true"});
  ASSERT_TRUE(s.walls.has_value());
  EXPECT_TRUE(s.walls->slip);
  EXPECT_TRUE(s.walls->virtual_particles);
  EXPECT_EQ(s.walls->virtual_flow, VirtualFlow::rest);
  EXPECT_FALSE(parse_scene(minimal_scene, "p.toml", {}).walls.has_value());
}

TEST(SceneErrors, BodyForceMixingValueAndSine) {
  bad(minimal_scene + "\n[body_force]\nkind = \"sine\"\namplitude = 0.1\nvalue = [0, 0, 0]\n",
      {"body_force.value", "sine"});
  bad(minimal_scene + "\n[body_force]\nvalue = [0.1, 0]\n", {"body_force.value", "3 entries"});
  bad(minimal_scene + "\n[body_force]\nkind = \"sine\"\n", {"body_force.amplitude", "missing"});
  bad(minimal_scene + "\n[body_force]\nkind = \"swirl\"\n", {"body_force.kind", "sine"});
}

TEST(SceneErrors, BadOutputKeys) {
  bad(with("output", "every = 0"), {"output.every = 0", ">= 1"});
  bad(with("output", "observables = [\"pressure\"]"), {"output.observables[0]", "temperature"});
  bad(with("output", "observables = \"temperature\""), {"output.observables", "(string)"});
  bad(with("output", "checkpoint_every = -1"), {"output.checkpoint_every = -1"});
}

TEST(SceneErrors, BadRunKeys) {
  bad(with("run", "seed = -1"), {"run.seed = -1", ">= 0"});
  bad(with("run", "steps = -5"), {"run.steps = -5", "from 0 to 9999999999"});
  bad(with("fluid", "sort_every = -1"), {"fluid.sort_every = -1"});
  bad(with("fluid", "kT = 0"), {"fluid.kT = 0"});
}

TEST(SceneErrors, SectionThatIsNotATable) {
  bad("fluid = 3\n" + minimal_scene.substr(0, minimal_scene.find("[fluid]")),
      {"fluid", "(integer)", "a table"});
}

} // namespace

// ---- [colloids] ---------------------------------------------------------------------------------

const std::string channel_scene = R"(
[run]
dimensions = 2
steps = 10

[domain]
size = [40, 10]

[fluid]
collision = "srd"
dt = 0.1

[walls]
)";

TEST(Scene, ColloidsDefaultsAndValues) {
  const Scene s = parse_scene(
      with("colloids", "radius = 2\ncount = 3\ngravity = [0.1, 0.0]", channel_scene), "c.toml");
  ASSERT_TRUE(s.colloids.has_value());
  const auto &c = *s.colloids;
  EXPECT_DOUBLE_EQ(c.radius, 2.0);
  EXPECT_EQ(c.count, 3);
  EXPECT_EQ(c.placement, ColloidPlacement::lattice);
  EXPECT_EQ(c.md_substeps, 15);
  EXPECT_DOUBLE_EQ(c.gravity[0], 0.1);
  EXPECT_DOUBLE_EQ(c.effective_wall_sigma(), 4.0);
  // Tabatabaei (2008) table 3.1: M = pi r^2 n = 125.664 for r = 2, n = 10
  EXPECT_NEAR(c.effective_mass(2, 10.0), 125.664, 1e-3);
  EXPECT_NEAR(c.effective_mass(3, 1.0), 4.0 / 3.0 * 3.14159265358979 * 8.0, 1e-12);
  const Scene l = parse_scene(
      with("colloids", "radius = 1\nplacement = \"list\"\npositions = [[5, 5], [20.5, 3]]",
           channel_scene),
      "c.toml");
  EXPECT_EQ(l.colloids->count, 2);
  EXPECT_DOUBLE_EQ(l.colloids->positions[1][0], 20.5);
  EXPECT_FALSE(parse_scene(minimal_scene, "m.toml").colloids.has_value());
  EXPECT_EQ(c.radius_sd, 0.0); // all radii equal
  EXPECT_EQ(c.max_radius(), 2.0);
  const Scene p = parse_scene(
      with("colloids", "radius = 1.5\nradius_sd = 0.1\ncount = 3", channel_scene), "c.toml");
  EXPECT_DOUBLE_EQ(p.colloids->radius_sd, 0.1);
  EXPECT_DOUBLE_EQ(p.colloids->max_radius(), 1.8);
  EXPECT_DOUBLE_EQ(p.colloids->wall_sigma_of(1.7), 3.4); // 2 r_a unless wall_sigma is set
  EXPECT_NEAR(p.colloids->mass_of(2, 10.0, 1.7), 3.14159265358979 * 1.7 * 1.7 * 10.0, 1e-9);
}

TEST(SceneErrors, ColloidsKeys) {
  const auto col = [](const std::string &lines) { return with("colloids", lines, channel_scene); };
  bad(col("count = 3"), {"colloids.radius", "missing"});
  bad(col("radius = -1\ncount = 3"), {"colloids.radius = -1", "> 0"});
  bad(col("radius = 2"), {"colloids.count", "missing"});
  bad(col("radius = 2\ncount = 11"), {"colloids.count = 11", "at most 10"});
  bad(col("radius = 2\ncount = 1\nmd_substeps = 0"), {"colloids.md_substeps = 0", "1 to 10000"});
  bad(col("radius = 2\ncount = 1\ngravity = [0.1]"), {"colloids.gravity", "2 entries"});
  bad(col("radius = 2\ncount = 1\nplacement = \"grid\""), {"colloids.placement", "lattice"});
  bad(col("radius = 2\ncount = 1\nradious = 2"), {"colloids.radious", "radius"});
  bad(col("radius = 2\ncount = 1\nwall_sigma = 5"), {"colloids.wall_sigma = 5", "half"});
  bad(col("radius = 3\ncount = 1"), {"colloids.wall_sigma", "2 radius = 6.0"});
  bad(col("radius = 1\nplacement = \"list\"\npositions = [[50, 5]]"),
      {"colloids.positions[0]", "outside the box"});
  bad(col("radius = 1\nplacement = \"list\"\ncount = 1\npositions = [[5, 5]]"),
      {"colloids.count", "cannot be mixed"});
  bad(col("radius = 1\ncount = 1\npositions = [[5, 5]]"), {"colloids.positions", "list"});
  bad(with("colloids", "radius = 1\ncount = 1\nwall_sigma = 1"),
      {"colloids.wall_sigma", "[walls]"});
  bad(col("radius = 1\ncount = 1\nmass = 0"), {"colloids.mass = 0"});
  // radius_sd: 0 to 0.2 radius; size checks use the largest radius, radius + 3 radius_sd.
  bad(col("radius = 2\ncount = 1\nradius_sd = -0.1"),
      {"colloids.radius_sd = -0.1", "out of range",
       "from 0 (all radii equal) to 0.2 radius = 0.4"});
  bad(col("radius = 2\ncount = 1\nradius_sd = 0.5"), {"colloids.radius_sd = 0.5", "0.2 radius"});
  bad(col("radius = 2\ncount = 1\nradius_sd = \"wide\""), {"colloids.radius_sd", "string"});
  bad(col("radius = 2\ncount = 1\nradius_sd = 0.2"),
      {"colloids.wall_sigma", "2 (radius + 3 radius_sd) = 5.2", "half the channel width"});
  bad(col("radius = 1\ncount = 13\nradius_sd = 0.2"),
      {"colloids.count = 13", "diameter 3.2", "radius + 3 radius_sd = 1.6", "at most 12"});
  bad(with("output", "observables = [\"settling_velocity\"]"),
      {"settling_velocity", "only with [colloids]"});
}

TEST(Scene, Thermostat) {
  const Scene s = parse_scene(with("thermostat", "kind = \"layers\"", channel_scene), "t.toml");
  ASSERT_TRUE(s.thermostat.has_value());
  EXPECT_EQ(s.thermostat->kind, ThermostatKind::layers);
  bad(with("thermostat", "kind = \"layer\"", channel_scene), {"thermostat.kind", "layers"});
  bad(with("thermostat", "", channel_scene), {"thermostat.kind", "missing"});
  bad(with("thermostat", "kind = \"layers\"\nevery = 2", channel_scene), {"thermostat.every"});
  bad(with("thermostat", "kind = \"layers\""), {"[thermostat]", "at+a", "srd"});
  const Scene m = parse_scene(
      with("thermostat", "kind = \"monte-carlo\"\ngamma = 0.3", channel_scene), "t.toml");
  EXPECT_EQ(m.thermostat->kind, ThermostatKind::monte_carlo);
  EXPECT_DOUBLE_EQ(m.thermostat->gamma, 0.3);
  bad(with("thermostat", "kind = \"layers\"\ngamma = 0.3", channel_scene),
      {"thermostat.gamma", "monte-carlo"});
  bad(with("thermostat", "kind = \"monte-carlo\"\ngamma = 2", channel_scene),
      {"thermostat.gamma = 2", "(0, 1]"});
}

// ---- hostile text (issue 18): limits checked before toml11 recurses or clamps ----------------

TEST(SceneHostile, DeepNestingIsRefusedBeforeTheParser) {
  bad("a = " + std::string(5000, '[') + std::string(5000, ']') + "\n",
      {"line 1", "brackets nested deeper than 64 levels"});
  std::string inline_tables = "a = ";
  for (int i = 0; i < 5000; ++i)
    inline_tables += "{b = ";
  bad(inline_tables + "1" + std::string(5000, '}') + "\n", {"brackets nested deeper than 64"});
  std::string dotted = "[a";
  for (int i = 0; i < 100000; ++i)
    dotted += ".a";
  bad(dotted + "]\n", {"dotted keys nested deeper than 64"});
  bad(dotted.substr(1) + " = 1\n", {"dotted keys nested deeper than 64"});
  // 64 levels are fine for the limit (the scene is refused for its unknown section instead).
  bad("a = " + std::string(64, '[') + std::string(64, ']') + "\n", {"unknown key 'a'"});
  // Brackets and dots inside strings and comments do not count.
  EXPECT_NO_THROW(
      parse_scene(with("output", "dir = \"" + std::string(200, '[') + "." + std::string(100, '.') +
                                     "\" # " + std::string(200, '{')),
                  "run/ok.toml"));
}

TEST(SceneHostile, EmptyBinaryAndHugeTextsAreRefused) {
  bad("", {"the scene file is empty"});
  bad("\n \n\t\n", {"the scene file is empty"});
  bad(minimal_scene.substr(0, 20) + std::string(1, '\0') + "garbage", {"byte 20 is NUL"});
  bad(std::string((16 << 20) + 1, ' '), {"16777217 bytes; allowed: at most 16777216"});
  bad(minimal_scene, {"--set", "brackets nested deeper"},
      {"fluid.dt=" + std::string(100, '[') + std::string(100, ']')});
}

TEST(SceneHostile, IntegersBeyond64BitsAreRefusedNotClamped) {
  bad(with("run", "seed = 99999999999999999999"),
      {"integer 99999999999999999999 is beyond 64 bits"});
  bad(with("run", "steps = 9_223_372_036_854_775_808"), {"beyond 64 bits"});
  bad(with("run", "steps = -9223372036854775809"), {"beyond 64 bits"});
  bad(minimal_scene, {"beyond 64 bits"}, {"run.seed=18446744073709551616"});
  // The extremes themselves are integers toml11 reads exactly (then checked by their keys).
  const auto s = parse_scene(with("run", "seed = 9223372036854775807"), "run/ok.toml");
  EXPECT_EQ(s.run.seed, 9223372036854775807ULL);
}

TEST(SceneHostile, ArraysParseInLinearTime) {
  std::string big = "[run]\nengine = \"mpcd\"\ndimensions = 2\nsteps = 1\n[domain]\nsize = [";
  for (int i = 0; i < 100000; ++i)
    big += "1.0, ";
  big += "1.0]\n";
  const auto start = std::chrono::steady_clock::now();
  bad(big, {"domain.size"});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0) << "1e5 array entries took " << seconds << " s";
}

TEST(SceneHostile, NonRegularFilesAreRefused) {
  const auto dir = std::filesystem::temp_directory_path() / "narrows_test_fifo";
  std::filesystem::create_directories(dir);
  const auto fifo = dir / "scene.toml";
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  try {
    load_scene(fifo.string());
    ADD_FAILURE() << "a FIFO was read";
  } catch (const Error &e) {
    EXPECT_EQ(e.code(), ExitCode::bad_input);
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneHostile, ViscosityNeedsThreeRowsAndLgcaAParticle) {
  bad(good_scene + "[walls]\n", {"domain.size[1] = 2", "allowed: domain.size[1] >= 3"},
      {"domain.size=[4.0, 2.0]", "output.observables=[\"viscosity\"]"});
  const std::string lgca = "[run]\nengine = \"lgca\"\nsteps = 10\n[lattice]\nmodel = \"fhp-i\"\n"
                           "size = [256, 128]\ndensity = 1e-9\n";
  bad(lgca, {"lattice.density = 1e-09 gives 0.000197 particles expected on 196608 links",
             "at least one"});
  bad("[run]\nengine = \"lgca\"\nsteps = 10\n[lattice]\nmodel = \"dhumieres-1d\"\nsize = [2]\n"
      "density = 0.5\n",
      {"lattice.size", "from 3 to"});
}

TEST(SceneHostile, RunStepsFitTheCheckpointName) {
  bad(with("run", "steps = 10000000000"), {"run.steps = 10000000000", "from 0 to 9999999999"});
  EXPECT_EQ(parse_scene(with("run", "steps = 9999999999"), "run/ok.toml").run.steps, 9999999999);
}

// [[colloids.kind]]: several kinds, ids kind by kind, count the total, radius the largest;
// the one-kind keys beside it, unknown keys and bad values are refused with one line.
TEST(Scene, ColloidKinds) {
  const std::string two = "placement = \"random\"\n[[colloids.kind]]\nradius = 1\ncount = 3\n"
                          "[[colloids.kind]]\nradius = 1.5\ncount = 2\nmass = 40\n";
  const Scene s = parse_scene(with("colloids", two, channel_scene), "c.toml");
  const auto &c = *s.colloids;
  ASSERT_EQ(c.kinds.size(), 2u);
  EXPECT_EQ(c.count, 5);
  EXPECT_EQ(c.kind_count(), 2u);
  EXPECT_DOUBLE_EQ(c.max_radius(), 1.5);
  EXPECT_EQ(c.kind_of(2), 0u);
  EXPECT_EQ(c.kind_of(3), 1u);
  EXPECT_EQ(c.kind_of(4), 1u);
  EXPECT_NEAR(c.mass_of_id(2, 10.0, 0, 1.0), 3.14159265358979 * 10.0, 1e-9); // density-matched
  EXPECT_DOUBLE_EQ(c.mass_of_id(2, 10.0, 3, 1.5), 40.0);                     // given
  // Statistics keys and their defaults.
  EXPECT_EQ(c.max_lag, 1000);
  EXPECT_EQ(c.correlation_every, 1);
  const Scene t = parse_scene(with("colloids",
                                   "radius = 1\ncount = 1\nmax_lag = 40\ncorrelation_every = 4\n"
                                   "kde_width = 0.5\nstatistics_from = 100",
                                   channel_scene),
                              "c.toml");
  EXPECT_EQ(t.colloids->max_lag, 40);
  EXPECT_EQ(t.colloids->correlation_every, 4);
  EXPECT_DOUBLE_EQ(t.colloids->kde_width, 0.5);
  EXPECT_EQ(t.colloids->statistics_from, 100);
  EXPECT_EQ(t.colloids->kind_count(), 1u);
  EXPECT_EQ(t.colloids->kind_of(0), 0u);
}

TEST(SceneErrors, ColloidKinds) {
  const auto col = [](const std::string &lines) { return with("colloids", lines, channel_scene); };
  const std::string kind = "[[colloids.kind]]\nradius = 1\ncount = 3\n";
  bad(col("radius = 1\n" + kind), {"colloids.radius = 1", "cannot be mixed", "[[colloids.kind]]"});
  bad(col("count = 2\n" + kind), {"colloids.count = 2", "cannot be mixed"});
  bad(col("mass = 2\n" + kind), {"colloids.mass = 2", "cannot be mixed"});
  bad(col("placement = \"list\"\n" + kind), {"colloids.placement", "\"lattice\" or \"random\""});
  bad(col(kind + "colour = 2\n"), {"colloids.kind[0].colour", "radius, count, mass"});
  bad(col("[[colloids.kind]]\ncount = 3\n"), {"colloids.kind[0].radius", "missing"});
  bad(col(kind + "[[colloids.kind]]\nradius = 1\n"), {"colloids.kind[1].count", "missing"});
  bad(col(kind + "[[colloids.kind]]\nradius = 1\ncount = 1\nmass = -1\n"),
      {"colloids.kind[1].mass = -1", "> 0"});
  bad(col("kind = 3"), {"colloids.kind", "array of tables"});
  bad(col("[[colloids.kind]]\nradius = 1\ncount = 30\n"), {"colloids.kind", "row along x"});
  bad(col("radius = 1\ncount = 1\ncorrelation_every = 3"),
      {"colloids.max_lag", "multiple of colloids.correlation_every = 3"});
  bad(col("radius = 1\ncount = 1\nmax_lag = 10\ncorrelation_every = 3"),
      {"colloids.max_lag = 10", "multiple"});
  bad(col("radius = 1\ncount = 1\nkde_width = 0"), {"colloids.kde_width = 0", "> 0"});
  bad(with("output", "observables = [\"density_kde\"]", channel_scene),
      {"density_kde", "[colloids]"});
}
