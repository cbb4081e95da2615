// The process's seconds in messages (see message_clock.hpp).
#include "narrows/parallel/message_clock.hpp"

namespace narrows::parallel {

namespace {
double total = 0.0; // (one per process: every exchange and collective of the process adds here)
} // namespace

double message_seconds() { return total; }

MessageTimer::MessageTimer() : timed_(total) {}

} // namespace narrows::parallel
