// Momentum and energy of fluid plus colloids.
#include "narrows/engines/mpcd/totals.hpp"

#include "narrows/colloids/hard_spheres.hpp"

#include "narrows/analysis/fluid_observables.hpp"

namespace narrows::mpcd {

namespace {

// The colloids' momentum added to the fluid's p, in id order (the same sum on any number of
// ranks).
void add_colloid_momentum(const colloids::Colloids &c, std::array<double, 3> &p) {
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < c.size(); ++a)
      p[k] += c.mass[a] * c.v[k][a];
}

} // namespace

std::array<double, 3> total_momentum(const MpcdSimulation &sim) {
  auto p = analysis::total_momentum(sim.fluid(), sim.comm()).value();
  if (sim.scene().colloids)
    add_colloid_momentum(sim.gather_colloids(), p);
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
  if (!sim.scene().colloids)
    return e;
  const colloids::Colloids c = sim.gather_colloids();
  for (int k = 0; k < c.dim; ++k)
    for (std::size_t a = 0; a < c.size(); ++a)
      e += 0.5 * c.mass[a] * c.v[k][a] * c.v[k][a];
  if (sim.md() == nullptr) { // no-slip colloids: no potentials, but they spin
    for (std::size_t a = 0; a < c.size(); ++a)
      for (int k = 0; k < 3; ++k)
        e += 0.5 * colloids::moment_of_inertia(c, a) * c.omega[k][a] * c.omega[k][a];
    return e;
  }
  return e + sim.md()->potential_energy(f, sim.colloids()).total();
}

void SettlingSum::add(const MpcdSimulation &sim) {
  const colloids::Colloids c = sim.gather_colloids();
  auto p = analysis::total_momentum(sim.fluid(), sim.comm()).value();
  add_colloid_momentum(c, p);
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

} // namespace narrows::mpcd
