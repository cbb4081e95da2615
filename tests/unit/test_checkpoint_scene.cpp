// The serial parts of checkpoint/restart: file names, the output.checkpoint_keep key, the
// canonical scene text and the comparison of a restart's scene with the checkpoint's.
#include "narrows/core/error.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/scene/canonical.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

using namespace narrows;

namespace {
const char *scene_text = R"(
[run]
engine = "mpcd"
dimensions = 2
steps = 100
[domain]
size = [8.0, 4.0]
[fluid]
collision = "srd"
dt = 0.5
)";

ExitCode code_of(const std::function<void()> &f) {
  try {
    f();
  } catch (const Error &e) {
    return e.code();
  }
  return ExitCode::ok;
}
} // namespace

TEST(CheckpointScene, FileNameHasTenDigitStep) {
  EXPECT_EQ(io::checkpoint_path("out/x", 1234), "out/x/checkpoint-0000001234.h5");
}

TEST(CheckpointScene, KeepDefaultsToTwoAndIsValidated) {
  EXPECT_EQ(scene::parse_scene(scene_text, "s.toml").output.checkpoint_keep, 2);
  EXPECT_EQ(
      scene::parse_scene(scene_text, "s.toml", {"output.checkpoint_keep=5"}).output.checkpoint_keep,
      5);
  EXPECT_EQ(code_of([] { scene::parse_scene(scene_text, "s.toml", {"output.checkpoint_keep=0"}); }),
            ExitCode::bad_input);
}

// The canonical text does not depend on comments, layout, key order or number spelling.
TEST(CheckpointScene, CanonicalTextIgnoresLayoutAndNumberSpelling) {
  const char *other_layout = R"(# the same scene, written differently
[fluid]
dt = 5e-1
collision = "srd"
[domain]
size = [8, 4.0]
[run]
steps = 100
dimensions = 2
engine = "mpcd"
)";
  EXPECT_EQ(scene::canonical_text(scene_text, "a"), scene::canonical_text(other_layout, "b"));
  EXPECT_EQ(scene::parse_scene(scene_text, "a").canonical, scene::canonical_text(scene_text, "a"));
  EXPECT_EQ(scene::canonical_text("[a]\nx = 0.1\ny = \"q\\\"\"\n", "c"),
            "a.x = 0.1\na.y = \"q\\\"\"\n");
}

// run.steps and output.* may differ; anything else is named, a deleted section as the section.
TEST(CheckpointScene, FirstDifferenceNamesTheKey) {
  const auto canon = [](const std::vector<std::string> &sets) {
    return scene::parse_scene(scene_text, "s.toml", sets).canonical;
  };
  EXPECT_FALSE(
      scene::first_difference(canon({"run.steps=500", "output.every=7"}), scene_text, "c"));
  const auto dt = scene::first_difference(canon({"fluid.dt=0.25"}), scene_text, "c");
  ASSERT_TRUE(dt);
  EXPECT_EQ(dt->key, "fluid.dt");
  EXPECT_EQ(dt->given, "0.25");
  EXPECT_EQ(dt->stored, "0.5");
  const auto walls = scene::first_difference(canon({"walls.slip=true"}), scene_text, "c");
  ASSERT_TRUE(walls);
  EXPECT_EQ(walls->key, "[walls]");
  const auto seed = scene::first_difference(canon({"run.seed=3"}), scene_text, "c");
  ASSERT_TRUE(seed);
  EXPECT_EQ(seed->key, "run.seed");
  EXPECT_EQ(seed->given, "3");
  EXPECT_EQ(seed->stored, "(not set: the default 42)");
  // A key not set equals its documented default (issue 35 item 4).
  EXPECT_FALSE(scene::first_difference(canon({"run.seed=42"}), scene_text, "c"));
  EXPECT_FALSE(scene::first_difference(canon({"run.seed=3"}), scene_text, "c", {"run.seed"}));
  EXPECT_EQ(code_of([] { scene::first_difference(scene_text, "[broken", "c.h5"); }),
            ExitCode::bad_input);
}
