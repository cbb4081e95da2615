// Invariant checks of an MPCD run.
#include "narrows/engines/mpcd/invariants.hpp"

#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/totals.hpp"

#include <cmath>
#include <sstream>

namespace narrows::mpcd {

namespace {

struct IdDigest {
  std::uint64_t count = 0, sum = 0, xr = 0;
};

IdDigest id_digest(const mpcd::Fluid &f, MPI_Comm comm) {
  std::uint64_t local[2] = {f.size(), 0}, lx = 0;
  for (auto id : f.id) {
    local[1] += id;
    lx ^= id;
  }
  IdDigest d;
  std::uint64_t global[2];
  MPI_Allreduce(local, global, 2, MPI_UINT64_T, MPI_SUM, comm);
  MPI_Allreduce(&lx, &d.xr, 1, MPI_UINT64_T, MPI_BXOR, comm);
  d.count = global[0];
  d.sum = global[1];
  return d;
}

[[noreturn]] void fail(const MpcdSimulation &sim, int rank, const std::string &what) {
  std::ostringstream os;
  os << "invariant broken at step " << sim.step() << " on rank " << rank << ": " << what;
  throw invariant_error(os.str());
}

} // namespace

InvariantCheck::InvariantCheck(const MpcdSimulation &sim) {
  const IdDigest d = id_digest(sim.fluid(), sim.comm());
  count_ = d.count;
  id_sum_ = d.sum;
  id_xor_ = d.xr;
  momentum0_ = total_momentum(sim); // fluid and colloids
  step0_ = sim.step();
  const auto &scene = sim.scene();
  const bool rule_conserves = scene.fluid.collision != scene::Collision::random_maxwell;
  double colloid_mass = 0.0; // of all colloids, in id order
  if (scene.colloids)
    for (const double m : sim.gather_colloids().mass)
      colloid_mass += m;
  for (int k = 0; k < sim.box().dim; ++k) {
    conserved_[k] = rule_conserves;
    if (scene.body_force && scene.body_force->kind == scene::ForceKind::sine && k == 0)
      conserved_[k] = false; // the sine force injects sum_i sin(k y_i), which fluctuates
    if (scene.body_force && scene.body_force->kind == scene::ForceKind::constant)
      drive_[k] = scene.body_force->value[k] * static_cast<double>(count_);
    if (scene.colloids) // gravity (and the drive) on the colloids: force M_a g on each
      drive_[k] += scene::colloid_acceleration(scene)[k] * colloid_mass;
    // No-slip walls and virtual particles exchange momentum with the fluid; slip walls
    // without virtual particles only reverse v_y, so along the walls the momentum is the force
    // impulse and is checked. In the other channels it is not: the momentum the walls take
    // (2 m v per bounce-back, the virtual particles' share of each wall-cell collision, the
    // wall potential on colloids) is not tallied by the kernels, and its running sum is a
    // random walk, so no bound on the fluid's momentum follows from the force impulse alone.
    // Those runs keep the count, id, finiteness, speed and inside-the-channel checks.
    if (scene.walls && (k == 1 || !scene.walls->slip || scene.walls->virtual_particles))
      conserved_[k] = false;
  }
}

void InvariantCheck::check(const MpcdSimulation &sim) const {
  int rank = 0;
  MPI_Comm_rank(sim.comm(), &rank);
  const auto &f = sim.fluid();
  // Local checks first: every rank looks at its own particles.
  int bad = 0;
  std::string what;
  for (int k = 0; k < f.dim && !bad; ++k)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double v = f.v[k][i], x = f.x[k][i];
      if (!std::isfinite(v) || !std::isfinite(x) || std::abs(v) > max_speed) {
        std::ostringstream os;
        os << "particle id " << f.id[i] << " has position " << x << " and velocity " << v
           << " along axis " << k << " (allowed: finite, |v| <= " << max_speed << ")";
        what = os.str();
        bad = 1;
        break;
      }
    }
  int any_bad = 0;
  MPI_Allreduce(&bad, &any_bad, 1, MPI_INT, MPI_MAX, sim.comm());
  if (bad)
    fail(sim, rank, what);
  if (any_bad)
    fail(sim, rank, "another rank found a non-finite or runaway particle");
  if (sim.box().walls_y) {
    const double L = sim.box().length[1];
    for (std::size_t i = 0; i < f.size() && !bad; ++i)
      if (!(f.x[1][i] >= 0.0 && f.x[1][i] <= L)) {
        std::ostringstream os;
        os.precision(17);
        os << "particle id " << f.id[i] << " is outside the channel at y = " << f.x[1][i]
           << " (allowed: 0 <= y <= " << L << ")";
        what = os.str();
        bad = 1;
      }
    MPI_Allreduce(&bad, &any_bad, 1, MPI_INT, MPI_MAX, sim.comm());
    if (bad)
      fail(sim, rank, what);
    if (any_bad)
      fail(sim, rank, "another rank found a particle outside the channel");
  }

  const IdDigest d = id_digest(f, sim.comm());
  if (d.count != count_ || d.sum != id_sum_ || d.xr != id_xor_) {
    std::ostringstream os;
    os << "particle count or id set changed: " << d.count << " particles (expected " << count_
       << ")";
    fail(sim, rank, os.str());
  }

  // Momentum: the fixed-point cell sums round each velocity by at most 2^-41, so a collision
  // step can move the total by at most N 2^-40 per component; allow twice that per step.
  const auto p = total_momentum(sim);
  const double n = static_cast<double>(count_);
  const double steps = static_cast<double>(sim.step() - step0_);
  // The thermostat rescales around fixed-point cell means too: the same bound once more.
  const double rounding_passes = sim.scene().thermostat ? 2.0 : 1.0;
  const double tol = 2.0 * rounding_passes * n * fixed::inv_scale * (steps + 1.0) + 1e-9;
  const double t = steps * sim.scene().fluid.dt;
  for (int k = 0; k < f.dim; ++k) {
    if (!conserved_[k])
      continue;
    const double expected = momentum0_[k] + drive_[k] * t;
    if (std::abs(p[k] - expected) > tol + 1e-12 * std::abs(expected)) {
      std::ostringstream os;
      os.precision(12);
      os << "total momentum along axis " << k << " is " << p[k] << ", expected " << expected
         << " (tolerance " << tol << ")";
      fail(sim, rank, os.str());
    }
  }
}

} // namespace narrows::mpcd
