// Stopping cleanly on SIGTERM / SIGUSR1 (what SLURM sends before the time limit).
#pragma once

#include <mpi.h>

#include <csignal>

namespace narrows::run {

// Installs handlers for SIGTERM and SIGUSR1 while alive; the previous handlers come back on
// destruction. main() holds one from before MPI_Init, so that no signal kills a run by the
// default action; a signal received at any time is kept until the run loop asks for it.
class StopSignals {
public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals &) = delete;
  StopSignals &operator=(const StopSignals &) = delete;
  // Collective: the signal received by any rank (0 if none), the same on every rank (or the
  // value a step's collective agreed on, if one was handed over since the last call).
  int requested(MPI_Comm comm) const;
  // This rank only (not collective, cheap): the signal received here, 0 if none.
  int received() const;

private:
  struct sigaction old_term_ {
  }, old_usr1_{};
};

const char *signal_name(int sig);

// This rank only (not collective): the stop signal received since the program started (0 if
// none), for work before the run loop (packing colloids) that polls it.
int stop_signal_received();

// A collective that a step runs anyway may carry the stop signal (its maximum over the ranks):
// the engine hands the agreed value here, on every rank alike, and the run loop's next poll
// (StopSignals::requested) takes it instead of a collective of its own.
void hand_agreed_stop_signal(int any);
// Drops a value handed over (the next poll is a collective again): after a step that a signal
// interrupted, which the value agreed at the step's start may not know of.
void forget_agreed_stop_signal();

} // namespace narrows::run
