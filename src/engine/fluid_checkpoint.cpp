// The MPCD fluid as a checkpoint species.
#include "narrows/engine/fluid_checkpoint.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::engine {

namespace {

// A restart from NaN or Inf would only break later, far from the cause: refuse it here, on every
// rank with the same line (collective), naming the dataset and the lowest particle id affected.
void refuse_non_finite_fluid(const std::string &path, const mpcd::Fluid &fluid, MPI_Comm comm) {
  constexpr std::uint64_t none = ~std::uint64_t{0};
  std::uint64_t bad = none; // id * 6 + (velocity ? 3 : 0) + component, lowest
  for (std::size_t i = 0; i < fluid.id.size(); ++i)
    for (int k = 0; k < fluid.dim; ++k) {
      if (!std::isfinite(fluid.x[k][i]))
        bad = std::min(bad, fluid.id[i] * 6 + static_cast<std::uint64_t>(k));
      if (!std::isfinite(fluid.v[k][i]))
        bad = std::min(bad, fluid.id[i] * 6 + 3 + static_cast<std::uint64_t>(k));
    }
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_UINT64_T, MPI_MIN, comm);
  if (bad == none)
    return;
  const bool velocity = bad % 6 >= 3;
  throw input_error(path + ": /particles/fluid/" + (velocity ? "velocity" : "position") +
                    "/value holds NaN or Inf (particle id " + std::to_string(bad / 6) +
                    ", component " + std::to_string(bad % 3) + "); allowed: finite numbers");
}

} // namespace

io::SpeciesFields fluid_fields(mpcd::Fluid &f) {
  io::SpeciesFields s;
  s.name = "fluid";
  s.dim = f.dim;
  s.vectors.push_back({"position", {&f.x[0], &f.x[1], &f.x[2]}});
  s.vectors.push_back({"velocity", {&f.v[0], &f.v[1], &f.v[2]}});
  s.words.push_back({"id", &f.id});
  return s;
}

mpcd::Fluid read_fluid(const std::string &path, const io::CheckpointInfo &info, MPI_Comm comm) {
  mpcd::Fluid fluid;
  fluid.dim = info.dimensions;
  auto fields = fluid_fields(fluid);
  io::read_species(path, fields, comm);
  refuse_non_finite_fluid(path, fluid, comm);
  fluid.cell.assign(fluid.id.size(), 0);
  for (const auto id : fluid.id)
    if (id >= info.fluid_particles)
      throw input_error(path + ": /particles/fluid/id/value holds id " + std::to_string(id) +
                        "; allowed: 0 to " + std::to_string(info.fluid_particles - 1));
  return fluid;
}

} // namespace narrows::engine
