// Momentum and energy of fluid plus colloids.
#include "narrows/engine/totals.hpp"

#include "narrows/analysis/fluid_observables.hpp"

namespace narrows::engine {

std::array<double, 3> total_momentum(const MpcdSimulation &sim) {
  auto p = analysis::total_momentum(sim.fluid(), sim.comm()).value();
  const auto &c = sim.colloids();
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < c.size(); ++a)
      p[k] += c.mass[a] * c.v[k][a];
  return p;
}

double total_energy(MpcdSimulation &sim) {
  const auto &f = sim.fluid();
  double kinetic = 0.0;
  for (int k = 0; k < f.dim; ++k)
    for (const double v : f.v[k])
      kinetic += 0.5 * v * v;
  double e = 0.0;
  MPI_Allreduce(&kinetic, &e, 1, MPI_DOUBLE, MPI_SUM, sim.comm());
  const auto &c = sim.colloids();
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < c.size(); ++a)
      e += 0.5 * c.mass[a] * c.v[k][a] * c.v[k][a];
  if (auto *md = sim.md())
    e += md->forces().compute(f, c, sim.comm(), true).total();
  return e;
}

void SettlingSum::add(const MpcdSimulation &sim) {
  const auto p = total_momentum(sim);
  const auto &c = sim.colloids();
  double mass = static_cast<double>(particle_count(sim.scene())); // fluid, m_f = 1
  for (std::size_t a = 0; a < c.size(); ++a)
    mass += c.mass[a];
  const double n = static_cast<double>(c.size());
  for (int k = 0; k < c.dim; ++k) {
    double v = 0.0;
    for (std::size_t a = 0; a < c.size(); ++a)
      v += c.v[k][a];
    sum_[k] += v / n - p[k] / mass;
  }
  ++steps_;
}

std::array<double, 3> SettlingSum::mean() const {
  std::array<double, 3> m{0.0, 0.0, 0.0};
  for (int k = 0; k < 3 && steps_ > 0; ++k)
    m[k] = sum_[k] / static_cast<double>(steps_);
  return m;
}

} // namespace narrows::engine
