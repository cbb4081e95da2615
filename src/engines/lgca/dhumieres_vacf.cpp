// Tagged-particle VACF of the 1D d'Humieres model (see lattice/dhumieres_vacf.hpp).
#include "narrows/engines/lgca/dhumieres_vacf.hpp"

#include "narrows/engines/lgca/moment_propagation.hpp"

#include <chrono>
#include <utility>

namespace narrows::lgca::dhumieres {

VacfRun measure_vacf(std::int64_t L, double d, Ensemble ensemble, Rule rule, std::uint64_t seed,
                     int max_lag, int curves, const std::function<bool()> &stop) {
  const auto t0 = std::chrono::steady_clock::now();
  auto state = initial_state(L, d, ensemble, seed);
  std::vector<std::uint8_t> next(state.size());
  const auto table = collision_table();
  MomentPropagation mp(link_velocities(), neighbours(L), max_lag);
  VacfRun run;
  run.particles = total_mass(state);
  run.momentum = total_momentum(state);
  mp.feed(state);
  for (std::uint64_t step = 1; mp.curves() < curves; ++step) {
    propagate(state, next);
    std::swap(state, next);
    collide(state, table, rule, seed + 1, step);
    mp.feed(state);
    if (stop && step % 4096 == 0 && stop()) {
      run.stopped = true;
      break;
    }
  }
  run.vacf = mp.mean();
  run.curves = mp.curves();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

} // namespace narrows::lgca::dhumieres
