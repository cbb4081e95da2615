// The serial parts of checkpoint/restart: file names, the output.checkpoint_keep key, which
// --set overrides a restart accepts, and the scene comparison with a checkpoint's scene.
#include "narrows/core/error.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <functional>

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

TEST(CheckpointScene, RestartAcceptsOnlyStepsAndOutputOverrides) {
  EXPECT_EQ(code_of([] {
              io::check_restart_overrides({"run.steps=10", "output.every=5"});
            }),
            ExitCode::ok);
  EXPECT_EQ(code_of([] { io::check_restart_overrides({"fluid.dt=0.1"}); }), ExitCode::bad_input);
  EXPECT_EQ(code_of([] { io::check_restart_overrides({"run.seed=3"}); }), ExitCode::bad_input);
}

TEST(CheckpointScene, RestartSceneMustMatchTheCheckpoint) {
  const auto stored = scene::parse_scene(scene_text, "s.toml");
  io::CheckpointInfo info;
  info.scene_text = scene_text;
  info.dimensions = 2;
  info.fluid_particles = 320;
  const auto longer = scene::parse_scene(scene_text, "s.toml", {"run.steps=500"});
  EXPECT_EQ(code_of([&] { io::check_restart_scene(longer, info, "c.h5"); }), ExitCode::ok);
  const auto other = scene::parse_scene(scene_text, "s.toml", {"fluid.dt=0.25"});
  EXPECT_EQ(code_of([&] { io::check_restart_scene(other, info, "c.h5"); }), ExitCode::bad_input);
  info.dimensions = 3;
  EXPECT_EQ(code_of([&] { io::check_restart_scene(stored, info, "c.h5"); }), ExitCode::bad_input);
  info.dimensions = 2;
  info.fluid_particles = 319;
  EXPECT_EQ(code_of([&] { io::check_restart_scene(stored, info, "c.h5"); }), ExitCode::bad_input);
}
