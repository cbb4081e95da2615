// Writing and reading the FHP lattice as the checkpoint species "lattice".
#include "narrows/lattice/fhp_checkpoint.hpp"

#include "narrows/core/error.hpp"

namespace narrows::lattice {

namespace {

std::size_t words_per_column(const FhpLattice &l) {
  return (static_cast<std::size_t>(l.size_y()) + 7) / 8;
}

io::SpeciesFields lattice_species(std::vector<std::uint64_t> &words) {
  io::SpeciesFields s;
  s.name = "lattice";
  s.dim = 2;
  s.words.push_back({"state", &words});
  return s;
}

} // namespace

double write_lattice_checkpoint(const std::string &path, const FhpLattice &l,
                                const std::string &scene_text, const std::string &canonical_scene) {
  const std::size_t wpc = words_per_column(l);
  std::vector<std::uint64_t> words(wpc * static_cast<std::size_t>(l.local_columns()), 0);
  for (int y = 0; y < l.size_y(); ++y) {
    const std::uint8_t *r = l.row(y);
    for (int x = 0; x < l.local_columns(); ++x)
      words[static_cast<std::size_t>(x) * wpc + static_cast<std::size_t>(y / 8)] |=
          static_cast<std::uint64_t>(r[x]) << (8 * (y % 8));
  }
  io::CheckpointInfo info;
  info.scene_text = scene_text;
  info.canonical_scene = canonical_scene;
  info.step = l.time();
  info.time = static_cast<double>(l.time());
  info.seed = l.params().seed;
  info.dimensions = 2;
  info.box = {static_cast<double>(l.size_x()), l.size_y() * 0.8660254037844386, 1.0};
  info.walls_y = l.params().walls;
  return io::write_checkpoint(path, info, {lattice_species(words)}, l.comm());
}

void read_lattice_checkpoint(const std::string &path, const io::CheckpointInfo &info,
                             FhpLattice &l) {
  const std::size_t wpc = words_per_column(l);
  std::vector<std::uint64_t> words;
  auto species = lattice_species(words);
  const std::uint64_t rows = io::species_rows(path, species, l.comm());
  const std::uint64_t want = wpc * static_cast<std::uint64_t>(l.size_x());
  if (rows != want)
    throw input_error(path + ": /particles/lattice/state/value has " + std::to_string(rows) +
                      " words, a " + std::to_string(l.size_x()) + " x " +
                      std::to_string(l.size_y()) + " lattice needs " + std::to_string(want) +
                      "; allowed: a checkpoint of this scene");
  io::read_species_rows(path, species, wpc * static_cast<std::uint64_t>(l.first_column()),
                        wpc * static_cast<std::uint64_t>(l.local_columns()), l.comm());
  for (int y = 0; y < l.size_y(); ++y) {
    std::uint8_t *r = l.row(y);
    for (int x = 0; x < l.local_columns(); ++x)
      r[x] = static_cast<std::uint8_t>(
          words[static_cast<std::size_t>(x) * wpc + static_cast<std::size_t>(y / 8)] >>
          (8 * (y % 8)));
  }
  l.set_time(info.step);
}

} // namespace narrows::lattice
