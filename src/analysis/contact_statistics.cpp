// Overlap histograms, sliding fractions and coordination numbers of a contact network.
#include "narrows/analysis/contact_statistics.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace narrows::analysis {

std::vector<double> ContactStatistics::bin_centres() {
  std::vector<double> c(bins);
  for (std::size_t b = 0; b < bins; ++b)
    c[b] = (static_cast<double>(b) + 0.5) * bin_width;
  return c;
}

ContactStatistics contact_statistics(const colloids::ContactNetwork &n,
                                     std::span<const std::uint64_t> ids,
                                     std::span<const std::size_t> kinds, std::size_t kind_count) {
  ContactStatistics s;
  for (auto &h : s.histogram)
    h.assign(ContactStatistics::bins, 0.0);
  std::vector<double> partners(ids.size(), 0.0);
  const auto row = [&](std::uint64_t id) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it == ids.end() || *it != id)
      throw Error(ExitCode::other, "contact statistics: no colloid " + std::to_string(id));
    return static_cast<std::size_t>(it - ids.begin());
  };
  for (std::size_t j = 0; j < n.size(); ++j) {
    const int w = n.is_wall(j) ? 1 : 0;
    const double b = std::floor(n.overlap[j] / n.scale[j] / ContactStatistics::bin_width);
    if (b < static_cast<double>(ContactStatistics::bins))
      s.histogram[w][static_cast<std::size_t>(b)] += 1.0;
    else
      s.beyond[w] += 1.0;
    s.contacts[w] += 1.0;
    s.sliding[w] += n.sliding[j];
    if (w == 0) {
      partners[row(n.owner[j])] += 1.0;
      partners[row(n.partner[j])] += 1.0;
    }
  }
  for (int w = 0; w < 2; ++w)
    s.sliding[w] = s.contacts[w] > 0.0 ? s.sliding[w] / s.contacts[w] : 0.0;
  std::vector<double> count(kind_count, 0.0);
  s.coordination.assign(kind_count, 0.0);
  for (std::size_t a = 0; a < ids.size(); ++a) {
    count[kinds[a]] += 1.0;
    s.coordination[kinds[a]] += partners[a];
  }
  for (std::size_t k = 0; k < kind_count; ++k)
    s.coordination[k] = count[k] > 0.0 ? s.coordination[k] / count[k] : 0.0;
  return s;
}

} // namespace narrows::analysis
