// Writing and reading the replicated colloid species of a checkpoint.
#include "narrows/io/colloid_checkpoint.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace narrows::io {

namespace {

// The stored fields of c: position, velocity, id.
SpeciesFields fields_of(colloids::Colloids &c) {
  SpeciesFields s;
  s.name = "colloids";
  s.dim = c.dim;
  s.vectors.push_back({"position", {&c.x[0], &c.x[1], &c.x[2]}});
  s.vectors.push_back({"velocity", {&c.v[0], &c.v[1], &c.v[2]}});
  s.words.push_back({"id", &c.id});
  return s;
}

} // namespace

SpeciesFields colloid_fields(colloids::Colloids &c, colloids::Colloids &empty, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    return fields_of(c);
  empty.dim = c.dim;
  empty.resize(0);
  return fields_of(empty);
}

colloids::Colloids read_colloids(const std::string &path, const scene::Colloids &spec, int dim,
                                 double density, MPI_Comm comm) {
  colloids::Colloids block;
  block.dim = dim;
  block.resize(0);
  SpeciesFields s = fields_of(block);
  read_species(path, s, comm);

  // Gather every rank's block everywhere: rows of 2 dim + 1 words.
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int row = 2 * dim + 1;
  const int mine = static_cast<int>(block.id.size());
  std::vector<int> counts(ranks), displs(ranks, 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<double> send(static_cast<std::size_t>(mine) * row);
  for (int i = 0; i < mine; ++i) {
    double *r = &send[static_cast<std::size_t>(i) * row];
    for (int k = 0; k < dim; ++k) {
      r[k] = block.x[k][i];
      r[dim + k] = block.v[k][i];
    }
    r[2 * dim] = static_cast<double>(block.id[i]); // ids < 2^53
  }
  int total = 0;
  for (int r = 0; r < ranks; ++r) {
    displs[r] = total * row;
    total += counts[r];
    counts[r] *= row;
  }
  if (total != spec.count)
    throw input_error(path + ": holds " + std::to_string(total) + " colloids, the scene has " +
                      std::to_string(spec.count) + "; allowed: a checkpoint of this scene");
  std::vector<double> all(static_cast<std::size_t>(total) * row);
  MPI_Allgatherv(send.data(), mine * row, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm);
  colloids::Colloids c;
  c.dim = dim;
  c.resize(static_cast<std::size_t>(total));
  const double mass = spec.effective_mass(dim, density);
  for (int i = 0; i < total; ++i) {
    const double *r = &all[static_cast<std::size_t>(i) * row];
    const auto id = static_cast<std::uint64_t>(r[2 * dim]);
    if (id >= static_cast<std::uint64_t>(total))
      throw input_error(path + ": /particles/colloids/id/value holds id " + std::to_string(id) +
                        "; allowed: 0 to " + std::to_string(total - 1));
    for (int k = 0; k < dim; ++k) {
      c.x[k][id] = r[k];
      c.v[k][id] = r[dim + k];
    }
    c.id[id] = id;
    c.radius[id] = spec.radius;
    c.mass[id] = mass;
  }
  return c;
}

} // namespace narrows::io
