// The run shell every engine uses: the restart (resolved, same scene, steps left), the output
// folder and its log, stop signals, the triggers of observables, trajectories and checkpoints,
// checkpoint rotation, progress with ETA, and the closing lines. An engine builds its state,
// asks the shell when to do what, and writes its own data; the shell owns everything else.
//
// Order of a run, so that a refusal writes nothing: Shell(...) checks the command line and the
// restart's header and scene (collectively: every rank ends with the same one line); the
// engine builds or reads its state (wrap reading in run::collectively); open() creates the
// folder and the log; the loop; the last checkpoint and the Loop time line. run::drive
// (run/drive.hpp) keeps this order for every engine.
#pragma once

#include "narrows/core/timer.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/run/log.hpp"
#include "narrows/run/stop_signals.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace narrows::run {

struct Options {
  std::string out_dir;    // overrides output.dir when not empty
  std::string restart;    // checkpoint file or directory to continue from (empty: fresh)
  bool overwrite = false; // a fresh run may replace the checkpoints of a run in out_dir
};

// What the shell needs to know of an engine's run.
struct RunSpan {
  std::int64_t end = 0;                // the step the run ends at (run.steps; kmc: replicas)
  const char *end_key = "run.steps";   // the scene key that sets it, for messages
  std::vector<std::string> may_change; // scene keys a restart may change besides run.steps
                                       // and output.* (kmc: "kmc.replicas")
};

// The scene a `narrows run --restart ARG` without a scene file continues: the checkpoint's
// own /parameters/scene with `sets` applied (collective; one line on bad input). Without
// --out the run continues in the checkpoint's directory (options.out_dir is set to it).
scene::Scene scene_of_checkpoint(Options &options, const std::vector<std::string> &sets,
                                 MPI_Comm comm);

class Shell {
public:
  // Checks before anything is written, collectively: a restart's checkpoint resolves, its
  // header reads, it was written by the same scene (scene::first_difference) and has steps
  // left (below span.end); a fresh run does not replace the checkpoints of a run in the
  // folder unless options.overwrite.
  Shell(const scene::Scene &scene, const Options &options, MPI_Comm comm, RunSpan span);

  bool restarting() const { return !restart_file_.empty(); }
  const std::string &restart_file() const { return restart_file_; }
  const io::CheckpointInfo &restart_info() const { return restart_info_; }
  const std::string &dir() const { return dir_; }
  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }

  // Creates the folder (removing the replaced run's checkpoints under --overwrite) and the
  // log DIR/log<suffix>.txt with the run's first line. `continued_from` >= 0 (a restart's
  // step) gives the files of this run the suffix "-<step as 10 digits>", so that they keep
  // what earlier runs wrote (log-0000001000.txt, observables-0000001000.h5).
  Log &open(std::int64_t continued_from);
  Log &log() { return log_; }
  // "DIR/<name><suffix>.h5"
  std::string output_file(const std::string &name) const;
  const std::string &suffix() const { return suffix_; }

  // ---- the loop --------------------------------------------------------------------------
  // Starts the loop clock (progress, Loop time) at step `first`.
  void start_loop(std::int64_t first);
  double loop_seconds() const { return clock_.seconds(); }
  bool observe_due(std::int64_t step) const {
    return step % scene_.output.every == 0 || step == span_.end;
  }
  bool trajectory_due(std::int64_t step) const {
    return scene_.output.trajectory_every > 0 && step % scene_.output.trajectory_every == 0;
  }
  bool checkpoint_due(std::int64_t step) const {
    const std::int64_t cadence = scene_.output.checkpoint_every;
    return cadence > 0 && step % cadence == 0 && step < span_.end;
  }
  // kmc: rounds of replicas advance by the rank count, so "at least output.checkpoint_every
  // since the checkpoint at `last`".
  bool checkpoint_due(std::int64_t step, std::int64_t last) const {
    const std::int64_t cadence = scene_.output.checkpoint_every;
    return cadence > 0 && step - last >= cadence && step < span_.end;
  }
  // Collective: a stop signal on any rank (remembered for finish()).
  bool stop_requested();
  // This rank only, cheap: for checks deep inside a step.
  bool stop_received() const { return signals_.received() != 0; }
  // A progress line every 10 s if output.progress (rate_unit nullptr: no rate).
  void progress(std::int64_t step, double per_step, const char *rate_unit,
                const char *what = "step");

  // ---- checkpoints -----------------------------------------------------------------------
  // The checkpoint header of this scene at `step`: scene text, canonical scene, seed.
  io::CheckpointInfo checkpoint_info(std::int64_t step, double time) const;
  // DIR/checkpoint-<step>.h5 written by `write(path)` (which returns what the log line says
  // after "checkpoint PATH: "), then the newest output.checkpoint_keep kept; returns the path.
  std::string checkpoint(std::int64_t step,
                         const std::function<std::string(const std::string &)> &write);

  // ---- the end ---------------------------------------------------------------------------
  // If a signal stopped the run: "received SIGTERM: stopped after <where>, checkpoint
  // <last> written; exit 0 (continue with --restart DIR)".
  void finish(const std::string &where, const std::string &last);
  bool stopped() const { return stop_ != 0; }
  void loop_time(double seconds, std::uint64_t count, const char *count_unit,
                 const std::string &with, double work, const char *rate_unit);

private:
  const scene::Scene &scene_;
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  RunSpan span_;
  Options options_;
  std::string dir_, suffix_, restart_file_;
  io::CheckpointInfo restart_info_;
  Log log_;
  StopSignals signals_;
  int stop_ = 0;
  std::int64_t first_ = 0;
  Stopwatch clock_, since_progress_;
};

} // namespace narrows::run
