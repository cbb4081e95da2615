// Statistics of a spring-contact network at one instant (observable contact_statistics, Kanehl
// (thesis) fig 6.2a): the histogram of the normal overlaps delta_n / a, colloid-colloid and
// colloid-wall apart, the fraction of contacts sliding, and the mean coordination number (colloid
// partners per colloid) of each kind.
//
// a is the smaller radius of the two colloids (the colloid's radius for a wall contact): the
// thesis gives overlaps "in units of colloidal radius" for a bidisperse suspension; measured in
// the smaller radius, delta / a is the relative depth in the disk that is pressed deeper, and a
// monodisperse packing reads as in the thesis. The bins are fixed, [0, 0.2) in steps of 0.002
// (100 bins): the thesis' statements (bulk 1-2 % deep, < 10 % deeper than 0.04 a) fall on bin
// edges, five bins per per cent resolve the peak, and 0.2 a is ten times the bulk; overlaps at or
// beyond 0.2 a are counted in `beyond`, so the counts add up to the contacts. Fixed bins make
// samples of different times, runs and rank counts add up directly.
#pragma once

#include "narrows/colloids/contact_network.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace narrows::analysis {

struct ContactStatistics {
  static constexpr std::size_t bins = 100;
  static constexpr double bin_width = 0.002; // of delta_n / a
  // [0] colloid-colloid, [1] colloid-wall.
  std::array<std::vector<double>, 2> histogram; // counts per bin [bins]
  std::array<double, 2> beyond{0.0, 0.0};       // overlaps >= bins * bin_width
  std::array<double, 2> contacts{0.0, 0.0};     // number of contacts
  std::array<double, 2> sliding{0.0, 0.0};      // fraction of them sliding (0 without contacts)
  std::vector<double> coordination;             // [kinds]: colloid partners per colloid
  static std::vector<double> bin_centres();
};

// The statistics of network `n`; `ids` every colloid's id, `kinds` its kind (0 .. kind_count -
// 1), in the same order.
ContactStatistics contact_statistics(const colloids::ContactNetwork &n,
                                     std::span<const std::uint64_t> ids,
                                     std::span<const std::size_t> kinds, std::size_t kind_count);

} // namespace narrows::analysis
