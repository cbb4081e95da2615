// The shock position of a profile (see continuum/shock.hpp).
#include "narrows/engines/continuum/shock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace narrows::continuum {

double shock_position(const std::vector<double> &u, double dx, bool periodic, std::size_t halo) {
  const auto n = static_cast<std::int64_t>(u.size());
  const std::int64_t faces = periodic ? n : n - 1; // face i between cells i and i+1
  const auto at = [&](std::int64_t i) {
    if (periodic)
      return u[static_cast<std::size_t>(((i % n) + n) % n)];
    return u[static_cast<std::size_t>(std::clamp<std::int64_t>(i, 0, n - 1))];
  };
  std::int64_t steep = 0;
  double best = -1.0;
  for (std::int64_t i = 0; i < faces; ++i) {
    const double jump = std::abs(at(i + 1) - at(i));
    if (jump > best) {
      best = jump;
      steep = i;
    }
  }
  const auto h = static_cast<std::int64_t>(halo);
  const double level = 0.5 * (at(steep - h) + at(steep + 1 + h));
  // The crossing of `level` nearest the steepest face (centres i and i+1, interpolated).
  double x = (static_cast<double>(steep) + 1.0) * dx;
  for (std::int64_t d = 0; d <= h; ++d) {
    bool found = false;
    for (const std::int64_t i : {steep - d, steep + d}) {
      if (!periodic && (i < 0 || i + 1 >= n))
        continue;
      const double a = at(i), b = at(i + 1);
      if ((a - level) * (b - level) <= 0.0 && a != b) {
        x = (static_cast<double>(i) + 0.5 + (level - a) / (b - a)) * dx;
        found = true;
        break;
      }
    }
    if (found)
      break;
  }
  if (periodic) {
    const double L = static_cast<double>(n) * dx;
    x = std::fmod(x, L);
    if (x < 0.0)
      x += L;
  }
  return x;
}

} // namespace narrows::continuum
