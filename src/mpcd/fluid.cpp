// Fluid storage and its initial state.
#include "narrows/mpcd/fluid.hpp"

#include "narrows/core/fixed_point.hpp"
#include "narrows/core/rng.hpp"

#include <cmath>

namespace narrows::mpcd {

Box make_periodic_box(int dim, std::array<int, 3> cells) {
  Box b;
  b.dim = dim;
  for (int k = 0; k < 3; ++k) {
    b.cells[k] = k < dim ? cells[k] : 1;
    b.length[k] = b.cells[k];
  }
  return b;
}

void Fluid::resize(std::size_t n) {
  for (int k = 0; k < 3; ++k) {
    x[k].resize(k < dim ? n : 0);
    v[k].resize(k < dim ? n : 0);
  }
  id.resize(n);
  cell.resize(n);
}

void init_fluid(Fluid &fluid, const Box &box, double density, double kT, std::uint64_t seed) {
  double volume = 1.0;
  for (int k = 0; k < box.dim; ++k)
    volume *= box.length[k];
  const auto n = static_cast<std::size_t>(std::llround(density * volume));
  fluid.dim = box.dim;
  fluid.resize(n);
  const double sigma = std::sqrt(kT);
  std::array<std::int64_t, 3> momentum{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    fluid.id[i] = i;
    const auto pos = rng::draw(seed, rng::Purpose::init_position, 0, i);
    const auto pos2 = rng::draw(seed, rng::Purpose::init_position, 1, i);
    const auto g = rng::gaussian4(rng::draw(seed, rng::Purpose::init_velocity, 0, i));
    for (int k = 0; k < box.dim; ++k) {
      const double u =
          k < 2 ? rng::uniform53(pos[2 * k], pos[2 * k + 1]) : rng::uniform53(pos2[0], pos2[1]);
      fluid.x[k][i] = u * box.length[k];
      fluid.v[k][i] = sigma * g[k];
      momentum[k] += fixed::from_double(fluid.v[k][i]);
    }
  }
  // Zero total momentum (seed 000 section 3.4.4): a net drift biases every flow measurement.
  for (int k = 0; k < box.dim; ++k) {
    const double mean = n ? fixed::to_double(momentum[k]) / static_cast<double>(n) : 0.0;
    for (auto &vk : fluid.v[k])
      vk -= mean;
  }
}

} // namespace narrows::mpcd
