// Checkpoint fields derived from a species table.
#include "narrows/io/species_fields.hpp"

#include "narrows/core/error.hpp"

namespace narrows::io {

namespace {

std::vector<double> *reals(const species::Field &f, int k) {
  auto *const *a = std::get_if<std::vector<double> *>(&f.column[k].array);
  if (a == nullptr)
    throw Error(ExitCode::other, "checkpoint field " + f.stored_name(k) + ": not of doubles");
  return *a;
}

} // namespace

SpeciesFields checkpoint_fields(const species::Table &t,
                                const std::function<bool(const species::Field &)> &skip) {
  SpeciesFields s;
  s.name = std::string(t.species());
  s.dim = t.dim();
  for (const species::Field &f : t.fields()) {
    if (!f.has(species::checkpoint) || (skip && skip(f)))
      continue;
    switch (f.shape) {
    case species::Shape::vector: {
      std::array<std::vector<double> *, 3> comp{};
      for (int k = 0; k < f.count; ++k)
        comp[k] = reals(f, k);
      s.vectors.push_back({std::string(f.name), comp});
      break;
    }
    case species::Shape::scalar:
      if (auto *const *w = std::get_if<std::vector<std::uint64_t> *>(&f.column[0].array))
        s.words.push_back({std::string(f.name), *w});
      else
        s.scalars.push_back({std::string(f.name), reals(f, 0)});
      break;
    case species::Shape::split:
      for (int k = f.first_stored; k < f.count; ++k)
        s.scalars.push_back({f.stored_name(k), reals(f, k)});
      break;
    }
  }
  return s;
}

bool has_checkpoint_field(const std::string &path, const species::Table &t, const species::Field &f,
                          MPI_Comm comm) {
  const int first = f.shape == species::Shape::split ? f.first_stored : 0;
  const int last = f.shape == species::Shape::split ? f.count : 1;
  for (int k = first; k < last; ++k)
    if (has_species_field(path, std::string(t.species()), f.stored_name(k), comm))
      return true;
  return false;
}

} // namespace narrows::io
