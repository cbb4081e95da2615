// Signal handlers that only set a flag; the run loop asks for it collectively.
#include "narrows/run/stop_signals.hpp"

namespace narrows::run {

namespace {
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) { stop_signal = sig; }
} // namespace

// The flag is not cleared here: main() installs the handlers before any work, and a signal
// that arrived before the run shell existed must still stop the run.
StopSignals::StopSignals() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, &old_term_);
  sigaction(SIGUSR1, &sa, &old_usr1_);
}

StopSignals::~StopSignals() {
  sigaction(SIGTERM, &old_term_, nullptr);
  sigaction(SIGUSR1, &old_usr1_, nullptr);
}

namespace {
int agreed_stop = -1; // handed over by a step's collective, -1 if none since the last poll
} // namespace

void hand_agreed_stop_signal(int any) { agreed_stop = any; }

void forget_agreed_stop_signal() { agreed_stop = -1; }

int StopSignals::requested(MPI_Comm comm) const {
  if (agreed_stop >= 0) { // (every rank handed the same value in the same step)
    const int any = agreed_stop;
    agreed_stop = -1;
    return any;
  }
  int local = stop_signal, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any;
}

int StopSignals::received() const { return stop_signal; }

int stop_signal_received() { return stop_signal; }

const char *signal_name(int sig) {
  switch (sig) {
  case SIGTERM:
    return "SIGTERM";
  case SIGUSR1:
    return "SIGUSR1";
  default:
    return "a signal";
  }
}

} // namespace narrows::run
