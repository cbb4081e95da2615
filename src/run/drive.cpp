// The run loop: one order of a step for every engine.
#include "narrows/run/drive.hpp"

namespace narrows::run {

void drive(Engine &engine, Shell &shell) {
  // The state first (a refusal writes nothing), then the folder, the log and the opening lines.
  engine.start(shell);
  Log &log = shell.open(shell.restarting() ? engine.step() : -1);
  engine.open(shell, log);

  const auto save = [&] {
    return shell.checkpoint(engine.step(), [&](const std::string &path) {
      return engine.write_checkpoint(shell, path);
    });
  };
  const RunSpan span = engine.span();
  Loop loop;
  loop.first = engine.step();
  std::int64_t last_checkpoint = loop.first;
  const Progress progress = engine.progress();
  shell.start_loop(loop.first);
  while (engine.step() < span.end) {
    if (!engine.advance()) { // a signal interrupted the step: every rank stops here
      forget_agreed_stop_signal();
      shell.stop_requested();
      break;
    }
    if (engine.observe_due(shell))
      engine.observe();
    if (shell.trajectory_due(engine.step()))
      engine.write_frame();
    // After the step in which a signal arrived, before its checkpoint: the last checkpoint
    // below is then of this step.
    if (shell.stop_requested())
      break;
    if (engine.keeps_checkpoints() && engine.checkpoint_due(shell, last_checkpoint)) {
      save();
      last_checkpoint = engine.step();
    }
    shell.progress(engine.step(), progress.per_step, progress.rate_unit, progress.what);
  }
  loop.seconds = shell.loop_seconds();
  loop.steps = engine.step() - loop.first;
  loop.stopped = shell.stopped();

  engine.finish(log, loop);
  if (engine.keeps_checkpoints())
    shell.finish(engine.where(), save());
  if (!loop.stopped)
    engine.summary(log, loop);
  const LoopTime t = engine.loop_time(loop);
  shell.loop_time(loop.seconds, t.count, t.count_unit, t.with, t.work, t.rate_unit);
}

} // namespace narrows::run
