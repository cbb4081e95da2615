// Streaming of fluid particles in a channel with planar walls at y = 0 and y = L_y: exact
// ballistic flight under a constant body force, with no-slip bounce-back (every velocity
// component reversed at the hit point) or slip (specular: v_y reversed) walls. The rest of the
// step after a hit is integrated with the force again, so several hits per step are handled.
#pragma once

#include "narrows/engines/mpcd/kernels/fluid.hpp"

#include <array>

namespace narrows::walls {

// Time until a particle at distance h >= 0 from a wall, with velocity u and acceleration a
// along the wall normal (pointing into the channel), first reaches the wall while moving
// outward: the smallest t >= 0 with h + u t + a t^2/2 = 0 and u + a t <= 0 (tangent grazes
// excluded), evaluated without cancellation. +infinity if it never does.
double time_to_wall(double h, double u, double a);

// Most hits a particle may make in one step before the rest of the step is flown without
// walls and clamped into the channel (only a particle resting on a wall under a force pushing
// it into the wall gets there: its hits come ever faster).
inline constexpr int max_hits_per_step = 64;

// Streams every particle by dt with acceleration `accel` (zero for free flight) inside the
// channel 0 <= y <= L_y, wraps x (and z) periodically. No particle ends outside the channel.
void stream_channel(mpcd::Fluid &fluid, const mpcd::Box &box, double dt,
                    const std::array<double, 3> &accel, bool slip);

} // namespace narrows::walls
