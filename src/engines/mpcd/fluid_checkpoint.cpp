// The MPCD fluid as a checkpoint species.
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/restart_checks.hpp"
#include "narrows/io/species_fields.hpp"

namespace narrows::mpcd {

io::SpeciesFields fluid_fields(mpcd::Fluid &f) { return io::checkpoint_fields(table(f)); }

mpcd::Fluid read_fluid(const std::string &path, const io::CheckpointInfo &info, MPI_Comm comm) {
  check_stored_scene(info, path);
  mpcd::Fluid fluid;
  fluid.dim = info.dimensions;
  auto fields = fluid_fields(fluid);
  io::read_species(path, fields, comm);
  check_restored_fluid(fluid, info, info.fluid_particles, path, comm);
  fluid.resize(fluid.id.size()); // fields a checkpoint does not hold (the cell): their fill
  return fluid;
}

} // namespace narrows::mpcd
