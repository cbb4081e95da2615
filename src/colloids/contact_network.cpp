// The contact network: overlaps, forces and sliding of the spring contacts from the positions and
// the contact history.
#include "narrows/colloids/contact_network.hpp"

#include "narrows/colloids/pair_geometry.hpp"
#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace narrows::colloids {

namespace {

std::size_t row_of(const Colloids &c, std::uint64_t id) {
  const auto it = std::lower_bound(c.id.begin(), c.id.end(), id);
  if (it == c.id.end() || *it != id)
    throw Error(ExitCode::other,
                "contact network: a contact names colloid " + std::to_string(id) + ", not held");
  return static_cast<std::size_t>(it - c.id.begin());
}

} // namespace

ContactNetwork contact_network(const Colloids &c, const ContactHistory &h, const mpcd::Box &box,
                               const SpringParams &p) {
  ContactNetwork out;
  const int D = box.dim;
  const auto &L = box.length;
  for (std::size_t q = 0; q < h.size(); ++q) {
    const std::size_t i = row_of(c, h.owner[q]);
    const bool wall = is_wall_id(h.partner[q]);
    const double ri = c.radius[i];
    double delta = 0.0, scale = ri;
    if (wall) { // (as the kernel: the overlap with the plane)
      const double y = c.x[1][i];
      delta = h.partner[q] == wall_low_id ? ri - y : y + ri - L[1];
    } else {
      const std::size_t j = row_of(c, h.partner[q]);
      double r2 = 0.0;
      for (int k = 0; k < D; ++k) {
        double d = c.x[k][j] - c.x[k][i]; // from i towards j
        if (!(box.walls_y && k == 1))
          d = minimum_image(d, L[k]);
        r2 += d * d;
      }
      delta = ri + c.radius[j] - std::sqrt(r2);
      scale = std::min(ri, c.radius[j]);
    }
    if (!(delta > 0.0))
      continue;
    double xi2 = 0.0;
    for (int k = 0; k < h.dim; ++k)
      xi2 += h.xi[k][q] * h.xi[k][q];
    const double mu = wall ? p.mu_cw : p.mu_cc;
    const double fn = p.kn * delta, ft = p.kt * std::sqrt(xi2);
    const bool slides =
        p.kt > 0.0 && std::isfinite(mu) && ft >= (1.0 - sliding_tolerance) * mu * fn;
    out.owner.push_back(h.owner[q]);
    out.partner.push_back(h.partner[q]);
    out.overlap.push_back(delta);
    out.scale.push_back(scale);
    out.normal.push_back(fn);
    out.tangential.push_back(ft);
    out.sliding.push_back(slides ? 1 : 0);
  }
  return out;
}

} // namespace narrows::colloids
