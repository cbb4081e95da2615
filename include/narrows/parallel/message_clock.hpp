// The seconds this process spends in messages: every halo exchange (Exchange) and the small
// collectives of a step, waiting for the other ranks included. A step's busy time is its wall
// time less these (slabs balanced by measured time, work_balance.hpp).
#pragma once

#include "narrows/core/timer.hpp"

namespace narrows::parallel {

// The process's total so far.
double message_seconds();

// Adds the seconds from its construction to its destruction to message_seconds().
class MessageTimer {
public:
  MessageTimer();
  MessageTimer(const MessageTimer &) = delete;
  MessageTimer &operator=(const MessageTimer &) = delete;

private:
  ScopedSeconds timed_;
};

} // namespace narrows::parallel
