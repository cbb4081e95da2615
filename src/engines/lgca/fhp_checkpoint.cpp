// Writing and reading the FHP lattice as the checkpoint species "lattice".
#include "narrows/engines/lgca/fhp_checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/io/hdf5.hpp"
#include "narrows/io/row_hash.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

namespace narrows::lgca {

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

namespace {

constexpr const char *checksum_name = "checksum"; // as io/checkpoint.cpp

std::string number_text(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// v wrapped into [0, l) as FhpColloid wraps its centre.
double wrapped(double v, double l) {
  v = std::fmod(v, l);
  if (v < 0.0)
    v += l;
  return v >= l ? v - l : v;
}

// A dataset of `values` (a scalar dataset if `scalar`) with its checksum attribute.
template <class T>
void write_checked(hid_t loc, const char *name, std::span<const T> values, const std::string &path,
                   bool scalar = false) {
  if (scalar)
    io::h5::write_scalar<T>(loc, name, values[0], path);
  else
    io::h5::write_dataset<T>(loc, name, values, path);
  const io::h5::Dataset d(H5Dopen2(loc, name, H5P_DEFAULT), path, std::string("open ") + name);
  const std::uint64_t sum = io::bytes_hash(values.data(), values.size_bytes());
  io::h5::write_attribute(d.get(), checksum_name, std::span<const std::uint64_t>(&sum, 1), path);
}

// Reads /colloid/... datasets of one checkpoint, each checked against its checksum.
class ColloidReader {
public:
  explicit ColloidReader(const std::string &path) : path_(path), file_(io::h5::open_file(path)) {
    // Checkpoints written before /colloid had checksums: values checked, damage not visible.
    checksums_ = exists("/colloid/momentum") && H5Aexists_by_name(file_.get(), "/colloid/momentum",
                                                                  checksum_name, H5P_DEFAULT) > 0;
  }
  bool checksums() const { return checksums_; }
  bool exists(const std::string &name) const {
    return H5Lexists(file_.get(), "/colloid", H5P_DEFAULT) > 0 &&
           (name.rfind("/colloid/correlations/", 0) != 0 ||
            H5Lexists(file_.get(), "/colloid/correlations", H5P_DEFAULT) > 0) &&
           H5Lexists(file_.get(), name.c_str(), H5P_DEFAULT) > 0;
  }
  // The values of dataset `name` (any shape, `size` values if size > 0), or nothing if it is
  // missing.
  template <class T>
  std::optional<std::vector<T>> read(const std::string &name, std::size_t size = 0) const {
    if (!exists(name))
      return std::nullopt;
    const hid_t d = H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT);
    if (d < 0)
      refuse("damaged checkpoint: HDF5 cannot open " + name);
    const hid_t space = H5Dget_space(d);
    const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
    if (space >= 0)
      H5Sclose(space);
    if (n < 0 || (size > 0 && static_cast<std::size_t>(n) != size)) {
      H5Dclose(d);
      refuse(name + " holds " + std::to_string(n) + " values; allowed: " + std::to_string(size) +
             " (a checkpoint of this scene)");
    }
    std::vector<T> v(static_cast<std::size_t>(n));
    const bool ok = n == 0 || H5Dread(d, io::h5::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                      v.data()) >= 0;
    std::optional<std::uint64_t> stored;
    const htri_t has = H5Aexists(d, checksum_name);
    if (has > 0) {
      const hid_t a = H5Aopen(d, checksum_name, H5P_DEFAULT);
      std::uint64_t sum = 0;
      const bool read_ok = a >= 0 && H5Aread(a, H5T_NATIVE_UINT64, &sum) >= 0;
      if (a >= 0)
        H5Aclose(a);
      if (!read_ok) {
        H5Dclose(d);
        refuse("damaged checkpoint: HDF5 cannot read " + name + " (its checksum)");
      }
      stored = sum;
    }
    H5Dclose(d);
    if (!ok)
      refuse("damaged checkpoint: HDF5 cannot read " + name);
    if (checksums_ && !stored)
      refuse("damaged checkpoint: " + name +
             " has no checksum, the other datasets have; allowed: a checkpoint as narrows run "
             "wrote it");
    const std::uint64_t sum = io::bytes_hash(v.data(), v.size() * sizeof(T));
    if (stored && *stored != sum) {
      char line[160];
      std::snprintf(line, sizeof line,
                    " does not match its checksum (stored %016llx, data %016llx)",
                    static_cast<unsigned long long>(*stored), static_cast<unsigned long long>(sum));
      refuse("damaged checkpoint: " + name + line +
             "; allowed: a checkpoint as narrows run wrote it, unmodified");
    }
    return v;
  }
  [[noreturn]] void refuse(const std::string &what) const {
    throw input_error(path_ + ": " + what);
  }
  // "PATH: NAME row I = V; allowed: ALLOWED"
  [[noreturn]] void bad_row(const std::string &name, std::size_t row, const std::string &value,
                            const std::string &allowed) const {
    refuse(name + " row " + std::to_string(row) + " = " + value + "; allowed: " + allowed);
  }
  void finite(const std::string &name, const std::vector<double> &v) const {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        bad_row(name, i, number_text(v[i]), "a finite number");
  }

private:
  std::string path_;
  io::h5::File file_;
  bool checksums_ = false;
};

} // namespace

void write_colloid_checkpoint(const std::string &path, const FhpColloid &c,
                              const ColloidCorrelations *stats) {
  const io::h5::File f = io::h5::open_file(path, H5F_ACC_RDWR);
  const io::h5::Group g = io::h5::create_group(f.get(), "colloid", path);
  const MomentumUnits p = c.momentum();
  write_checked<std::int64_t>(g.get(), "momentum", p, path);
  const double omega = c.omega(), angle = c.angle();
  write_checked<double>(g.get(), "omega", std::span<const double>(&omega, 1), path, true);
  const std::array<double, 2> x = c.position();
  write_checked<double>(g.get(), "position", x, path);
  write_checked<double>(g.get(), "angle", std::span<const double>(&angle, 1), path, true);
  if (stats != nullptr) {
    const ColloidCorrelations::State st = stats->state();
    const io::h5::Group h = io::h5::create_group(g.get(), "correlations", path);
    write_checked<std::int64_t>(h.get(), "layout", st.layout, path);
    write_checked<double>(h.get(), "values", st.values, path);
  }
}

ColloidCheckpoint read_colloid_checkpoint(const std::string &path, const FhpLattice &lattice,
                                          const ColloidParams &params) {
  io::h5::silence_errors();
  const ColloidReader in(path);
  const auto momentum = in.read<std::int64_t>("/colloid/momentum", 2);
  const auto omega = in.read<double>("/colloid/omega", 1);
  if (!momentum || !omega)
    in.refuse("no /colloid/{momentum, omega}; allowed: a checkpoint of a run with [colloid]");
  int rank = 0;
  MPI_Comm_rank(lattice.comm(), &rank);
  if (!in.checksums() && rank == 0)
    std::fprintf(stderr,
                 "warning: %s: /colloid carries no checksums (written by a narrows before they "
                 "existed); its values are checked, damage to them cannot be told\n",
                 path.c_str());
  ColloidCheckpoint c;
  c.momentum = {(*momentum)[0], (*momentum)[1]};
  in.finite("/colloid/omega", *omega);
  c.omega = (*omega)[0];

  // A held disc stays at colloid.position and never turns; a moving one is somewhere on the
  // (periodic) lattice, its centre wrapped into it. Checkpoints of held discs written before
  // position and angle were stored have neither.
  const double lx = lattice.size_x(), ly = lattice.size_y() * 0.8660254037844386;
  const auto position = in.read<double>("/colloid/position", 2);
  if (!position && !params.held)
    in.refuse("no /colloid/position (a checkpoint of a held disc) for a scene with "
              "colloid.held = false; allowed: a checkpoint of this scene");
  const std::array<double, 2> home{wrapped(params.x, lx), wrapped(params.y, ly)};
  c.position = {params.x, params.y};
  if (position) {
    in.finite("/colloid/position", *position);
    for (std::size_t k = 0; k < 2; ++k) {
      const double edge = k == 0 ? lx : ly, v = (*position)[k];
      if (!(v >= 0.0 && v < edge))
        in.bad_row("/colloid/position", k, number_text(v),
                   "0 <= value < " + number_text(edge) + " (the lattice's " +
                       (k == 0 ? "size_x" : "size_y sqrt(3)/2") + ")");
      if (params.held && v != home[k])
        in.bad_row("/colloid/position", k, number_text(v),
                   number_text(home[k]) + " (colloid.held = true: the disc stays at "
                                          "colloid.position)");
      c.position[k] = v;
    }
  }
  if (const auto angle = in.read<double>("/colloid/angle", 1)) {
    in.finite("/colloid/angle", *angle);
    if (params.held && (*angle)[0] != 0.0)
      in.bad_row("/colloid/angle", 0, number_text((*angle)[0]),
                 "0 (colloid.held = true: the disc does not turn)");
    c.angle = (*angle)[0];
  }

  // The averages: the layout (lags, blocks, steps) decides whether they are continued
  // (ColloidCorrelations::restore); every entry is a count or a lag, every value finite.
  const auto layout = in.read<std::int64_t>("/colloid/correlations/layout");
  const auto values = in.read<double>("/colloid/correlations/values");
  if (layout && values) {
    for (std::size_t i = 0; i < layout->size(); ++i)
      if ((*layout)[i] < (i == 4 ? 1 : 0))
        in.bad_row("/colloid/correlations/layout", i, std::to_string((*layout)[i]),
                   i == 4 ? "at least 1 (steps per block)" : "at least 0 (a lag or a count)");
    in.finite("/colloid/correlations/values", *values);
    c.correlations.layout = *layout;
    c.correlations.values = *values;
  }
  return c;
}

} // namespace narrows::lgca
