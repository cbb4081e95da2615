// Colloid paths over one step.
#include "narrows/colloids/paths.hpp"

#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/kernels/streaming.hpp"

#include <cmath>
#include <sstream>

namespace narrows::colloids {

void move_ballistic(Colloids &c, std::size_t rows, const mpcd::Box &box, double t) {
  for (std::size_t a = 0; a < rows; ++a)
    for (int k = 0; k < c.dim; ++k) {
      double x = c.x[k][a] + c.v[k][a] * t;
      if (!(k == 1 && box.walls_y))
        x = mpcd::wrap_periodic(x, box.length[k]);
      c.x[k][a] = x;
    }
}

void check_paths(const Colloids &c, std::size_t owned,
                 const std::array<std::vector<double>, 3> &start, const std::vector<double> &margin,
                 const mpcd::Box &box, double slack, const char *allowed) {
  check_paths(c, 0, owned, start, margin, box, slack, allowed);
}

void check_paths(const Colloids &c, std::size_t from, std::size_t to,
                 const std::array<std::vector<double>, 3> &start, const std::vector<double> &margin,
                 const mpcd::Box &box, double slack, const char *allowed) {
  for (std::size_t a = from; a < to; ++a) {
    double d2 = 0.0;
    for (int k = 0; k < c.dim; ++k) {
      double d = c.x[k][a] - start[k][a];
      if (!(k == 1 && box.walls_y))
        d = minimum_image(d, box.length[k]);
      d2 += d * d;
    }
    if (std::sqrt(d2) > margin[a] + slack) {
      std::ostringstream os;
      os << "colloid id " << c.id[a] << " moved " << std::sqrt(d2) << " in one step, more than the "
         << margin[a] << " " << allowed;
      throw invariant_error(os.str());
    }
  }
}

} // namespace narrows::colloids
