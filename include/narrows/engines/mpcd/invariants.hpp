// Runtime invariants of an MPCD run, checked on a schedule: particle count and id set, no
// NaN or runaway speed, total momentum where the scene conserves it.
#pragma once

#include "narrows/engines/mpcd/simulation.hpp"

#include <array>
#include <cstdint>

namespace narrows::mpcd {

// Largest particle speed accepted: keeps every fixed-point cell sum far inside its range.
inline constexpr double max_speed = 1.0e4;

class InvariantCheck {
public:
  // Records the reference state (call before the first step).
  explicit InvariantCheck(const MpcdSimulation &sim);
  // Throws narrows::Error(ExitCode::invariant) naming the step, the rank and what broke.
  void check(const MpcdSimulation &sim) const;

private:
  std::uint64_t count_ = 0;
  std::uint64_t id_sum_ = 0, id_xor_ = 0;
  std::array<double, 3> momentum0_{};
  std::int64_t step0_ = 0;
  std::array<bool, 3> conserved_{false, false, false}; // which components to check
  std::array<double, 3> drive_{0.0, 0.0, 0.0};         // constant force: dP/dt = N g
};

} // namespace narrows::mpcd
