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
  // Collective: the signal received by any rank (0 if none), the same on every rank.
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

} // namespace narrows::run
