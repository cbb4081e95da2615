// One engine as the run loop sees it (run/drive.hpp): a scene's state that advances step by
// step, and what it writes when the run shell's triggers fire. mpcd, lgca, kmc and continuum
// each implement it (engines/<name>/driver.hpp: make_engine); main.cpp picks one from its table
// of engines. The engine says WHAT a step, an observation or a checkpoint is; run::drive alone
// says WHEN, so that the engines cannot drift apart in the order of a step again.
#pragma once

#include "narrows/run/log.hpp"
#include "narrows/run/shell.hpp"

#include <cstdint>
#include <string>

namespace narrows::run {

// What the loop of a run did, for the lines that close it.
struct Loop {
  std::int64_t first = 0; // the step the loop started at
  std::int64_t steps = 0; // steps done by this run
  double seconds = 0.0;   // wall time of the loop on this rank
  bool stopped = false;   // a stop signal ended it before run.steps
};

// The figures of the progress lines: what one step updates (particles, sites), its unit per
// second (nullptr: no rate), and what a step is called ("replica 8 / 16").
struct Progress {
  double per_step = 0.0;
  const char *rate_unit = nullptr;
  const char *what = "step";
};

// The figures of the closing "Loop time of T s on P ranks for <count> <count_unit> with <with>
// (<work / T> <rate_unit>/s)" line.
struct LoopTime {
  std::uint64_t count = 0;
  const char *count_unit = "steps";
  std::string with;
  double work = 0.0;
  const char *rate_unit = "";
};

class Engine {
public:
  virtual ~Engine() = default;

  // ---- before anything is written (a refusal is collective: run::collectively) -----------
  // The step the run ends at, for the run shell (kmc: the replicas).
  virtual RunSpan span() const = 0;
  // Builds the state: the scene's initial state for a fresh run, the checkpoint's
  // (shell.restart_file()) on a restart.
  virtual void start(Shell &shell) = 0;

  // ---- once the folder and the log exist -------------------------------------------------
  // The log's opening lines (what will run, warnings, where a restart continues), the
  // observables file, and what is written before the first step.
  virtual void open(Shell &shell, Log &log) = 0;

  // ---- the loop (run::drive calls these in one fixed order) ------------------------------
  // The step the state is at (kmc: replicas done).
  virtual std::int64_t step() const = 0;
  // One step (kmc: one round of replicas, one per rank). false, the same on every rank: a stop
  // signal interrupted the step and nothing advanced (kmc drops the unfinished round).
  virtual bool advance() = 0;
  // Whether observables are due after this step (the continuum models: at their samples).
  virtual bool observe_due(const Shell &shell) const { return shell.observe_due(step()); }
  // Checks the invariants and writes the observables of this step.
  virtual void observe() = 0;
  // Writes a trajectory frame (when output.trajectory_every is due).
  virtual void write_frame() {}
  // Whether a checkpoint is due after this step; `last` is the step of the last checkpoint, or
  // the first step (kmc: at least output.checkpoint_every replicas since `last`, as its rounds
  // advance by the rank count).
  virtual bool checkpoint_due(const Shell &shell, std::int64_t last) const {
    (void)last;
    return shell.checkpoint_due(step());
  }
  // Writes the checkpoint of this step to `path` (collective); returns what the log says after
  // "checkpoint PATH: ".
  virtual std::string write_checkpoint(Shell &shell, const std::string &path) = 0;
  // Engines without checkpoints (lgca's d'Humieres model) write none, not even at the end, and
  // say themselves in finish() why a stop signal leaves nothing.
  virtual bool keeps_checkpoints() const { return true; }
  virtual Progress progress() const = 0;

  // ---- the end ---------------------------------------------------------------------------
  // Lines and results of the run, stopped or not, before the last checkpoint.
  virtual void finish(Log &log, const Loop &loop) {
    (void)log;
    (void)loop;
  }
  // Lines and results only a complete run has, after the last checkpoint (not after a stop).
  virtual void summary(Log &log, const Loop &loop) {
    (void)log;
    (void)loop;
  }
  // Where a stopped run stands, for "received SIGTERM: stopped after <where>, ...".
  virtual std::string where() const { return "step " + std::to_string(step()); }
  virtual LoopTime loop_time(const Loop &loop) const = 0;
};

} // namespace narrows::run
