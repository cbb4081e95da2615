// Writing and reading the FHP lattice as the checkpoint species "lattice".
#include "narrows/lattice/fhp_checkpoint.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <array>

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

// Calls f(index of the word, the rows 8 b .. 8 b + n - 1, n, column x) for every word of the
// checkpoint layout (column x's word b holds rows 8 b .. 8 b + 7, one byte each). The lattice is
// stored by rows, the checkpoint by columns: a tile of 64 columns at a time keeps both sides in
// cache (row by row over the whole width took 35 s for a 32768^2 lattice, one TLB miss per
// byte; tiled it takes about a second).
template <class Lattice, class F> void for_each_word(Lattice &l, F &&f) {
  const std::size_t wpc = words_per_column(l);
  const int nx = l.local_columns(), ny = l.size_y();
  constexpr int tile = 64;
  for (int x0 = 0; x0 < nx; x0 += tile) {
    const int x1 = std::min(nx, x0 + tile);
    for (std::size_t b = 0; b < wpc; ++b) {
      const int y0 = static_cast<int>(8 * b), n = std::min(8, ny - y0);
      std::array<decltype(l.row(0)), 8> rows{};
      for (int k = 0; k < n; ++k)
        rows[k] = l.row(y0 + k);
      for (int x = x0; x < x1; ++x)
        f(static_cast<std::size_t>(x) * wpc + b, rows, n, x);
    }
  }
}

} // namespace

double write_lattice_checkpoint(const std::string &path, const FhpLattice &l,
                                const std::string &scene_text, const std::string &canonical_scene) {
  const std::size_t wpc = words_per_column(l);
  std::vector<std::uint64_t> words(wpc * static_cast<std::size_t>(l.local_columns()), 0);
  for_each_word(l, [&](std::size_t at, const auto &rows, int n, int x) {
    std::uint64_t w = 0;
    for (int k = 0; k < n; ++k)
      w |= static_cast<std::uint64_t>(rows[k][x]) << (8 * k);
    words[at] = w;
  });
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
  for_each_word(l, [&](std::size_t at, const auto &rows, int n, int x) {
    for (int k = 0; k < n; ++k)
      rows[k][x] = static_cast<std::uint8_t>(words[at] >> (8 * k));
  });
  l.set_time(info.step);
}

} // namespace narrows::lattice
