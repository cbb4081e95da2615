// The MPCD observable axial_fields (see the header).
#include "narrows/engines/mpcd/axial_fields.hpp"

#include "narrows/analysis/axial_fields.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace narrows::mpcd {

AxialFields::AxialFields(const Box &box, double bin) : box_(box) {
  bins_ = analysis::axial_bin_count(box.length[0], bin);
  if (bins_ == 0)
    throw Error(ExitCode::other, "axial_fields: a " + std::to_string(box.dim) + "D box of length " +
                                     std::to_string(box.length[0]) + " in bins of " +
                                     std::to_string(bin));
  const double w = box.length[0] / static_cast<double>(bins_);
  for (std::size_t b = 0; b < bins_; ++b)
    centres_.push_back((static_cast<double>(b) + 0.5) * w);
}

AxialSample AxialFields::colloid_fields(const colloids::Colloids &all) const {
  if (box_.dim == 3) {
    auto f = analysis::colloid_axial_fields_3d(all.x[0], all.x[1], all.x[2], all.radius, all.v[0],
                                               box_.length, !box_.walls_y, bins_);
    return {std::move(f.phi), std::move(f.velocity), {}, std::move(f.local_fraction)};
  }
  auto f = analysis::colloid_axial_fields(all.x[0], all.x[1], all.radius, all.v[0],
                                          {box_.length[0], box_.length[1]}, !box_.walls_y, bins_);
  AxialSample s;
  s.phi = std::move(f.phi);
  s.velocity = std::move(f.velocity);
  s.local_fraction = std::move(f.local_fraction);
  return s;
}

AxialSample AxialFields::sample(const colloids::Colloids &all, const Fluid &fluid,
                                MPI_Comm comm) const {
  AxialSample s = colloid_fields(all);
  // This rank's sums per bin: count, and sum of v_x in fixed point as a 128-bit integer (a bin
  // of a long channel holds more momentum than one 64-bit fixed-point sum can), sent as two
  // 64-bit words each and added on rank 0: exact, so the order of ranks and particles is
  // irrelevant.
  const double scale = static_cast<double>(bins_) / box_.length[0];
  std::vector<std::uint64_t> mine(3 * bins_, 0); // per bin: count, low word, high word
  std::vector<__int128> sum(bins_, 0);
  std::vector<std::uint64_t> count(bins_, 0);
  const auto &x = fluid.x[0], &v = fluid.v[0];
  const auto last = static_cast<std::int64_t>(bins_) - 1;
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    const auto b = static_cast<std::size_t>(
        std::clamp(static_cast<std::int64_t>(std::floor(x[i] * scale)), std::int64_t{0}, last));
    ++count[b];
    sum[b] += fixed::from_double(v[i]);
  }
  for (std::size_t b = 0; b < bins_; ++b) {
    const auto u = static_cast<unsigned __int128>(sum[b]);
    mine[3 * b] = count[b];
    mine[3 * b + 1] = static_cast<std::uint64_t>(u);
    mine[3 * b + 2] = static_cast<std::uint64_t>(u >> 64);
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::vector<std::uint64_t> every(rank == 0 ? mine.size() * ranks : 0);
  MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_UINT64_T, every.data(),
             static_cast<int>(mine.size()), MPI_UINT64_T, 0, comm);
  if (rank != 0)
    return s;
  s.fluid_velocity.assign(bins_, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t b = 0; b < bins_; ++b) {
    unsigned __int128 total = 0; // two's complement: wrapping unsigned addition is exact
    std::uint64_t n = 0;
    for (int r = 0; r < ranks; ++r) {
      const std::uint64_t *w = &every[(static_cast<std::size_t>(r) * bins_ + b) * 3];
      n += w[0];
      total += static_cast<unsigned __int128>(w[1]) | (static_cast<unsigned __int128>(w[2]) << 64);
    }
    if (n > 0)
      s.fluid_velocity[b] = static_cast<double>(static_cast<__int128>(total)) * fixed::inv_scale /
                            static_cast<double>(n);
  }
  return s;
}

void AxialFields::add_local_fraction(colloids::Colloids &all) const {
  // A field of the trajectory only (no migration, ghosts or checkpoints): computed from the
  // gathered colloids when a frame is written.
  all.extra.add<double>(std::string(voronoi_fraction_field), species::trajectory, all.size()) =
      colloid_fields(all).local_fraction;
}

} // namespace narrows::mpcd
