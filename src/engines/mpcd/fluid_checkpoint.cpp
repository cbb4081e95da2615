// The MPCD fluid as a checkpoint species.
#include "narrows/engines/mpcd/fluid_checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/restart_checks.hpp"

namespace narrows::mpcd {

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
  check_stored_scene(info, path);
  mpcd::Fluid fluid;
  fluid.dim = info.dimensions;
  auto fields = fluid_fields(fluid);
  io::read_species(path, fields, comm);
  check_restored_fluid(fluid, info, info.fluid_particles, path, comm);
  fluid.cell.assign(fluid.id.size(), 0);
  return fluid;
}

} // namespace narrows::mpcd
