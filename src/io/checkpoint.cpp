// Checkpoints: collective parallel-HDF5 write and read, run-directory bookkeeping.
#include "narrows/io/checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/io/direct_writer.hpp"
#include "narrows/io/hdf5.hpp"
#include "narrows/io/row_hash.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

namespace narrows::io {

namespace fs = std::filesystem;

std::size_t SpeciesFields::rows() const {
  if (!words.empty())
    return words.front().second->size();
  if (!vectors.empty())
    return vectors.front().second[0]->size();
  if (!scalars.empty())
    return scalars.front().second->size();
  return 0;
}

namespace {

// Rows moved per collective H5Dread: bounds the staging buffer (4-12 MiB).
constexpr std::uint64_t rows_per_call = std::uint64_t{1} << 19;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int size_of(MPI_Comm comm) {
  int p = 1;
  MPI_Comm_size(comm, &p);
  return p;
}

[[noreturn]] void refuse(const std::string &path, const std::string &what) {
  throw input_error(path + ": " + what);
}

std::string hdf5_error_text();

std::string number_text(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// HDF5 could not read a dataset of a checkpoint that opened: its metadata are damaged.
[[noreturn]] void damaged(const std::string &path, const std::string &dataset) {
  const std::string err = hdf5_error_text();
  refuse(path, "damaged checkpoint: HDF5 cannot read " + dataset +
                   (err.empty() ? std::string() : " (" + err + ")") +
                   "; allowed: a checkpoint as narrows run wrote it");
}

// The file-access list of collective I/O on comm: metadata operations collective too, large
// datasets aligned to 1 MiB (file-system blocks).
h5::PropList mpio_fapl(MPI_Comm comm, const std::string &where) {
  h5::PropList fapl(H5Pcreate(H5P_FILE_ACCESS), where, "create file access list");
  h5::check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), where, "set MPI-IO driver");
  h5::check(H5Pset_all_coll_metadata_ops(fapl.get(), true), where, "set collective metadata");
  h5::check(H5Pset_coll_metadata_write(fapl.get(), true), where, "set collective metadata");
  h5::check(H5Pset_alignment(fapl.get(), 1 << 20, 1 << 20), where, "set alignment");
  // The 1.10 format checksums all metadata (superblock, object headers, attributes), so a
  // damaged header is refused by HDF5; the data carry our own checksums (checksum_attribute).
  h5::check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_V110), where,
            "set format bounds");
  return fapl;
}

h5::PropList collective_dxpl(const std::string &where) {
  h5::PropList dxpl(H5Pcreate(H5P_DATASET_XFER), where, "create transfer list");
  h5::check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), where, "set collective transfer");
  // Each rank's rows are one contiguous block per dataset, so MPI-IO's two-phase aggregation
  // only adds a shuffle between ranks: the call stays collective, the I/O underneath is each
  // rank's own (2.5x faster on a local disk). NARROWS_CHECKPOINT_TWO_PHASE=1 restores
  // aggregation (parallel file systems with many ranks per node may prefer it).
  if (std::getenv("NARROWS_CHECKPOINT_TWO_PHASE") == nullptr)
    h5::check(H5Pset_dxpl_mpio_collective_opt(dxpl.get(), H5FD_MPIO_INDIVIDUAL_IO), where,
              "set individual I/O under the collective call");
  return dxpl;
}

// Fixed-length strings: parallel HDF5 1.10 cannot write variable-length data.
h5::Datatype fixed_string(std::size_t n, const std::string &where) {
  h5::Datatype t(H5Tcopy(H5T_C_S1), where, "copy string type");
  h5::check(H5Tset_size(t.get(), std::max<std::size_t>(n, 1)), where, "set string size");
  h5::check(H5Tset_strpad(t.get(), H5T_STR_NULLPAD), where, "set string padding");
  h5::check(H5Tset_cset(t.get(), H5T_CSET_UTF8), where, "set string charset");
  return t;
}

void string_attribute(hid_t obj, const std::string &name, const std::string &value,
                      const std::string &where) {
  const auto type = fixed_string(value.size(), where);
  std::string buf = value;
  buf.resize(std::max<std::size_t>(value.size(), 1), '\0');
  h5::write_attribute(obj, name, type.get(), {}, buf.data(), where);
}

// Every dataset of a checkpoint carries the checksum of its data (io/row_hash.hpp) in this
// attribute; the value must be the same on every rank (attributes are written collectively).
constexpr const char *checksum_name = "checksum";

void checksum_attribute(hid_t dset, std::uint64_t sum, const std::string &where) {
  h5::write_attribute(dset, checksum_name, std::span<const std::uint64_t>(&sum, 1), where);
}

// A small dataset created by all ranks (collective) and written by rank 0 (independent); its
// checksum is rank 0's (other ranks may pass no data).
void small_dataset(hid_t loc, const std::string &name, hid_t type, std::span<const hsize_t> dims,
                   const void *data, MPI_Comm comm, const std::string &where) {
  const auto space = h5::simple_dataspace(dims, {}, where);
  const h5::Dataset d(
      H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      where, "create dataset " + name);
  std::uint64_t sum = 0;
  if (rank_of(comm) == 0) {
    std::size_t bytes = H5Tget_size(type);
    for (const hsize_t n : dims)
      bytes *= n;
    sum = bytes_hash(data, bytes);
  }
  MPI_Bcast(&sum, 1, MPI_UINT64_T, 0, comm);
  checksum_attribute(d.get(), sum, where);
  if (rank_of(comm) == 0)
    h5::check(H5Dwrite(d.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), where,
              "write dataset " + name);
}
template <class T>
void small_scalar(hid_t loc, const std::string &name, T value, MPI_Comm comm,
                  const std::string &where) {
  small_dataset(loc, name, h5::native_type<T>(), {}, &value, comm, where);
}
void small_string(hid_t loc, const std::string &name, const std::string &value, MPI_Comm comm,
                  const std::string &where) {
  const auto type = fixed_string(value.size(), where);
  std::string buf = value;
  buf.resize(std::max<std::size_t>(value.size(), 1), '\0');
  small_dataset(loc, name, type.get(), {}, buf.data(), comm, where);
}

// This rank's rows [offset, offset + n) of a [total][width] dataset, moved in collective calls
// of at most rows_per_call rows; every rank makes the same number of calls. `move(buf, first,
// count)` fills (write) or drains (read) the staging buffer for local rows [first, first+count).
// This rank's rows [offset, offset + n) of a [total][width] dataset, read in collective calls
// of at most rows_per_call rows; every rank makes the same number of calls. `move(buf, first,
// count)` drains the staging buffer into local rows [first, first + count).
// Returns the checksum of the rows read (io/row_hash.hpp; T is 8 bytes wide).
template <class T>
std::uint64_t read_rows(hid_t dset, std::uint64_t offset, std::uint64_t n, int width, MPI_Comm comm,
                        const std::function<void(T *, std::size_t, std::size_t)> &move,
                        const std::string &where, const std::string &name) {
  static_assert(sizeof(T) == 8);
  std::uint64_t sum = 0;
  std::uint64_t most = 0;
  MPI_Allreduce(&n, &most, 1, MPI_UINT64_T, MPI_MAX, comm);
  const std::uint64_t calls = (most + rows_per_call - 1) / rows_per_call;
  const auto dxpl = collective_dxpl(where);
  const h5::Dataspace file_space(H5Dget_space(dset), where, "get dataspace");
  const int rank = H5Sget_simple_extent_ndims(file_space.get());
  std::vector<T> buf(std::min(n, rows_per_call) * width);
  for (std::uint64_t c = 0; c < calls; ++c) {
    const std::uint64_t first = std::min(n, c * rows_per_call);
    const std::uint64_t count = std::min(n - first, rows_per_call);
    const hsize_t start[2] = {offset + first, 0};
    const hsize_t extent[2] = {count, static_cast<hsize_t>(width)};
    const hsize_t mem_dims[2] = {std::max<hsize_t>(count, 1), static_cast<hsize_t>(width)};
    const h5::Dataspace mem(H5Screate_simple(rank, mem_dims, nullptr), where, "memory space");
    if (count > 0) {
      h5::check(
          H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, extent, nullptr),
          where, "select rows");
    } else {
      h5::check(H5Sselect_none(file_space.get()), where, "select none");
      h5::check(H5Sselect_none(mem.get()), where, "select none");
    }
    if (H5Dread(dset, h5::native_type<T>(), mem.get(), file_space.get(), dxpl.get(), buf.data()) <
        0)
      damaged(where, name);
    if (count > 0) {
      sum += rows_hash(offset + first, buf.data(), count, width);
      move(buf.data(), first, count);
    }
  }
  return sum;
}

// The particle data of one dataset that this rank writes once the file's structure exists:
// rows [offset, offset + n) of `width` 8-byte values at file address `address`.
struct RowJob {
  std::uint64_t address = 0, offset = 0, n = 0;
  int width = 1;
  std::array<const std::vector<double> *, 3> components{}; // vector field (width components)
  const std::vector<std::uint64_t> *words = nullptr;       // or a word field
};

// Writes a job's rows, interleaving vector components into rows as the dataset stores them.
void write_job(const std::string &path, const RowJob &job) {
  const std::uint64_t row_bytes = 8 * static_cast<std::uint64_t>(job.width);
  DirectWriter out(path, job.address + job.offset * row_bytes,
                   job.address + (job.offset + job.n) * row_bytes);
  if (job.words != nullptr) {
    out.append(job.words->data(), job.n * 8);
  } else {
    constexpr std::size_t rows = 1 << 16;
    std::vector<double> buf(rows * job.width);
    for (std::uint64_t first = 0; first < job.n; first += rows) {
      const std::size_t count = std::min<std::uint64_t>(rows, job.n - first);
      for (int k = 0; k < job.width; ++k) {
        const double *src = job.components[k]->data() + first;
        for (std::size_t i = 0; i < count; ++i)
          buf[i * job.width + k] = src[i];
      }
      out.append(buf.data(), count * row_bytes);
    }
  }
  out.finish();
}

// A big dataset: space allocated at creation (required in parallel), never filled.
h5::Dataset create_rows(hid_t loc, const std::string &name, hid_t type, std::uint64_t total,
                        int width, bool vector, const std::string &where) {
  const hsize_t dims[2] = {total, static_cast<hsize_t>(width)};
  const auto space =
      h5::simple_dataspace(std::span<const hsize_t>(dims, vector ? 2 : 1), {}, where);
  h5::PropList dcpl(H5Pcreate(H5P_DATASET_CREATE), where, "create dataset list");
  h5::check(H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY), where, "set allocation time");
  h5::check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_NEVER), where, "set fill time");
  return h5::Dataset(
      H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), where,
      "create dataset " + name);
}

// Exclusive prefix sum and total of the local row counts.
std::pair<std::uint64_t, std::uint64_t> offset_and_total(std::uint64_t n, MPI_Comm comm) {
  std::uint64_t offset = 0, total = 0;
  MPI_Exscan(&n, &offset, 1, MPI_UINT64_T, MPI_SUM, comm);
  if (rank_of(comm) == 0)
    offset = 0; // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&n, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  return {offset, total};
}

// Creates the groups and datasets of a species (collective) and lists this rank's row jobs;
// the rows are written after the file is closed (write_job). Returns the bytes of all ranks.
double create_species(hid_t particles, const SpeciesFields &s, const CheckpointInfo &info,
                      MPI_Comm comm, const std::string &where, std::vector<RowJob> &jobs) {
  const std::uint64_t n = s.rows();
  const auto [offset, total] = offset_and_total(n, comm);
  const auto g = h5::create_group(particles, s.name, where);
  {
    const auto box = h5::create_group(g.get(), "box", where);
    const std::int32_t dim = s.dim;
    h5::write_attribute(box.get(), "dimension", std::span<const std::int32_t>(&dim, 1), where);
    const auto type = fixed_string(8, where);
    std::vector<char> boundary(8 * s.dim, '\0');
    for (int k = 0; k < s.dim; ++k)
      if (k == 1 && info.walls_y)
        std::memcpy(&boundary[8 * k], "none", 4);
      else
        std::memcpy(&boundary[8 * k], "periodic", 8);
    const hsize_t d = s.dim;
    h5::write_attribute(box.get(), "boundary", type.get(), std::span<const hsize_t>(&d, 1),
                        boundary.data(), where);
    small_dataset(box.get(), "edges", H5T_NATIVE_DOUBLE, std::span<const hsize_t>(&d, 1),
                  info.box.data(), comm, where);
  }
  double bytes = 0;
  RowJob pending; // the field being created: its data, before it has an address
  // The checksum of all ranks' rows, known before the rows are written (attributes are metadata).
  auto checksum = [&](const RowJob &job) {
    std::uint64_t local = 0;
    if (job.words != nullptr) {
      local = rows_hash(offset, job.words->data(), n, 1);
    } else {
      const double *cols[3] = {};
      for (int k = 0; k < job.width; ++k)
        cols[k] = job.components[k]->data();
      local = job.width == 1   ? columns_hash<1>(offset, cols, n)
              : job.width == 2 ? columns_hash<2>(offset, cols, n)
                               : columns_hash<3>(offset, cols, n);
    }
    std::uint64_t sum = 0;
    MPI_Allreduce(&local, &sum, 1, MPI_UINT64_T, MPI_SUM, comm);
    return sum;
  };
  auto field = [&](const std::string &name, hid_t type, int width, bool vector) {
    const auto fg = h5::create_group(g.get(), name, where);
    small_scalar<std::int64_t>(fg.get(), "step", info.step, comm, where);
    small_scalar<double>(fg.get(), "time", info.time, comm, where);
    const auto dset = create_rows(fg.get(), "value", type, total, width, vector, where);
    checksum_attribute(dset.get(), checksum(pending), where);
    const haddr_t address = H5Dget_offset(dset.get());
    if (address == HADDR_UNDEF)
      h5::fail(where, "get the file address of " + name);
    bytes += static_cast<double>(total) * width * 8;
    RowJob job = pending;
    job.address = address;
    job.offset = offset;
    job.n = n;
    job.width = width;
    return job;
  };
  for (const auto &[name, comp] : s.vectors) {
    pending = RowJob{};
    pending.width = s.dim;
    for (int k = 0; k < s.dim; ++k)
      pending.components[k] = comp[k];
    jobs.push_back(field(name, H5T_IEEE_F64LE, s.dim, true));
  }
  for (const auto &[name, words] : s.words) {
    pending = RowJob{};
    pending.words = words;
    jobs.push_back(field(name, H5T_STD_U64LE, 1, false));
  }
  for (const auto &[name, values] : s.scalars) {
    pending = RowJob{};
    pending.components[0] = values;
    jobs.push_back(field(name, H5T_IEEE_F64LE, 1, false));
  }
  return bytes;
}

// fsync of a file or directory; false on failure.
bool sync_path(const std::string &path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0)
    return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

// ---- reading ---------------------------------------------------------------------------------

// What HDF5 said about the last failure (its error stack, innermost first), for messages.
std::string hdf5_error_text() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t *e, void *data) -> herr_t {
        auto &t = *static_cast<std::string *>(data);
        if (e->desc != nullptr && *e->desc != '\0')
          t += std::string(t.empty() ? "" : "; ") + e->desc;
        return 0;
      },
      &text);
  return text;
}

// Whether every link of an absolute path exists.
bool path_exists(hid_t file, const std::string &path) {
  for (std::size_t pos = path.find('/', 1);; pos = path.find('/', pos + 1)) {
    if (H5Lexists(file, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0)
      return false;
    if (pos == std::string::npos)
      return true;
  }
}

h5::Dataset open_required(hid_t file, const std::string &name, const std::string &path) {
  if (!path_exists(file, name))
    refuse(path, "missing dataset " + name + "; allowed: a narrows checkpoint (format version " +
                     std::to_string(checkpoint_format_version) + ", written by narrows run)");
  h5::Dataset d(H5Dopen2(file, name.c_str(), H5P_DEFAULT));
  if (!d)
    damaged(path, name);
  return d;
}

// A checkpoint that open_checkpoint accepted, opened again by a reader of its datasets
// (collective); HDF5 failing now means damaged metadata.
h5::File open_readable(const std::string &path, MPI_Comm comm) {
  h5::silence_errors();
  const auto fapl = mpio_fapl(comm, path);
  h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()));
  if (!file)
    damaged(path, "the file's metadata");
  return file;
}

// Checkpoints written before checksums existed carry none (not even on /parameters/scene).
bool has_checksums(hid_t file) {
  return H5Aexists_by_name(file, "/parameters/scene", checksum_name, H5P_DEFAULT) > 0;
}

// The checksum stored with dataset `name`; none for a checkpoint without checksums; refused
// if the file has checksums but this dataset lost its own.
std::optional<std::uint64_t> stored_checksum(hid_t file, hid_t dset, const std::string &name,
                                             const std::string &path) {
  const htri_t exists = H5Aexists(dset, checksum_name);
  if (exists > 0) {
    const h5::Attribute a(H5Aopen(dset, checksum_name, H5P_DEFAULT));
    std::uint64_t sum = 0;
    if (!a || H5Aread(a.get(), H5T_NATIVE_UINT64, &sum) < 0)
      damaged(path, name + " (its checksum)");
    return sum;
  }
  if (exists == 0 && !has_checksums(file))
    return std::nullopt;
  refuse(path, "damaged checkpoint: " + name +
                   " has no checksum, the other datasets have; allowed: a checkpoint as narrows "
                   "run wrote it");
}

void verify_checksum(const std::optional<std::uint64_t> &stored, std::uint64_t computed,
                     const std::string &name, const std::string &path) {
  if (!stored || *stored == computed)
    return;
  char line[160];
  std::snprintf(line, sizeof line, " does not match its checksum (stored %016llx, data %016llx)",
                static_cast<unsigned long long>(*stored),
                static_cast<unsigned long long>(computed));
  refuse(path, "damaged checkpoint: " + name + line +
                   "; allowed: a checkpoint as narrows run wrote it, unmodified");
}

std::vector<hsize_t> shape_of(hid_t dset, const std::string &path) {
  const h5::Dataspace s(H5Dget_space(dset));
  if (!s)
    damaged(path, "a dataspace");
  const int n = H5Sget_simple_extent_ndims(s.get());
  std::vector<hsize_t> dims(std::max(n, 0));
  if (n > 0)
    H5Sget_simple_extent_dims(s.get(), dims.data(), nullptr);
  return dims;
}

// verify = false: the value before its checksum is checked (the format version, which a
// later narrows may have changed on purpose, is refused as such).
template <class T>
T read_scalar(hid_t file, const std::string &name, const std::string &path, bool verify = true) {
  const auto d = open_required(file, name, path);
  if (!shape_of(d.get(), path).empty())
    refuse(path, name + " is not a scalar; allowed: a narrows checkpoint");
  T value{};
  if (H5Dread(d.get(), h5::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) < 0)
    damaged(path, name);
  if (verify)
    verify_checksum(stored_checksum(file, d.get(), name, path), bytes_hash(&value, sizeof value),
                    name, path);
  return value;
}

std::string read_string(hid_t file, const std::string &name, const std::string &path) {
  const auto d = open_required(file, name, path);
  const h5::Datatype type(H5Dget_type(d.get()));
  if (!type)
    damaged(path, name);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    refuse(path, name + " is not a fixed-length string; allowed: a narrows checkpoint");
  std::string buf(H5Tget_size(type.get()), '\0');
  if (H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    damaged(path, name);
  verify_checksum(stored_checksum(file, d.get(), name, path), bytes_hash(buf.data(), buf.size()),
                  name, path);
  buf.resize(std::strlen(buf.c_str()));
  return buf;
}

std::string shape_text(const std::vector<hsize_t> &dims) {
  std::string s;
  for (const auto d : dims) {
    s += '[';
    s += std::to_string(d);
    s += ']';
  }
  return s.empty() ? "scalar" : s;
}

// Verifies the checksum of a small dataset the reader does not otherwise need (the step and
// time of each particle field): read as stored, byte for byte.
void verify_small(hid_t file, const std::string &name, const std::string &path) {
  const auto d = open_required(file, name, path);
  const h5::Datatype type(H5Dget_type(d.get()));
  const h5::Dataspace space(H5Dget_space(d.get()));
  const hssize_t count = space ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (!type || count < 0 || count > (1 << 20))
    damaged(path, name);
  std::vector<char> bytes(H5Tget_size(type.get()) * static_cast<std::size_t>(count));
  if (H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0)
    damaged(path, name);
  verify_checksum(stored_checksum(file, d.get(), name, path),
                  bytes_hash(bytes.data(), bytes.size()), name, path);
}

// A box's edge lengths [dim] (checksum verified): finite and > 0.
std::array<double, 3> read_edges(hid_t file, const std::string &name, int dim,
                                 const std::string &path) {
  const auto d = open_required(file, name, path);
  const auto shape = shape_of(d.get(), path);
  if (shape != std::vector<hsize_t>{static_cast<hsize_t>(dim)})
    refuse(path,
           name + " has shape " + shape_text(shape) + "; allowed: [" + std::to_string(dim) + "]");
  std::array<double, 3> edges{1.0, 1.0, 1.0};
  if (H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, edges.data()) < 0)
    damaged(path, name);
  verify_checksum(stored_checksum(file, d.get(), name, path),
                  bytes_hash(edges.data(), 8 * static_cast<std::size_t>(dim)), name, path);
  for (int k = 0; k < dim; ++k)
    if (!(edges[k] > 0.0 && std::isfinite(edges[k])))
      refuse(path, name + "[" + std::to_string(k) + "] = " + number_text(edges[k]) +
                       "; allowed: a finite length > 0");
  return edges;
}

} // namespace

namespace {

double write_checkpoint_via_tmp(const std::string &path, const CheckpointInfo &info,
                                const std::vector<SpeciesFields> &species, MPI_Comm comm,
                                const std::vector<CheckpointArray> &arrays) {
  h5::silence_errors();
  const std::string tmp = path + ".tmp";
  const auto fapl = mpio_fapl(comm, tmp);
  double bytes = 0;
  std::vector<RowJob> jobs;
  {
    h5::File file = h5::create_file(tmp, fapl.get());
    {
      const auto h5md = h5::create_group(file.get(), "h5md", tmp);
      const std::int32_t version[2] = {1, 1};
      h5::write_attribute(h5md.get(), "version", std::span<const std::int32_t>(version, 2), tmp);
      const auto creator = h5::create_group(h5md.get(), "creator", tmp);
      string_attribute(creator.get(), "name", "narrows", tmp);
      string_attribute(creator.get(), "version", NARROWS_VERSION, tmp);
      const auto author = h5::create_group(h5md.get(), "author", tmp);
      string_attribute(author.get(), "name", "narrows run", tmp);
    }
    {
      const auto params = h5::create_group(file.get(), "parameters", tmp);
      small_string(params.get(), "scene", info.scene_text, comm, tmp);
      if (!info.canonical_scene.empty())
        small_string(params.get(), "canonical_scene", info.canonical_scene, comm, tmp);
      small_scalar<std::int64_t>(params.get(), "step", info.step, comm, tmp);
      small_scalar<double>(params.get(), "time", info.time, comm, tmp);
      small_scalar<std::uint64_t>(params.get(), "seed", info.seed, comm, tmp);
      small_scalar<std::int64_t>(params.get(), "format_version", checkpoint_format_version, comm,
                                 tmp);
      small_scalar<std::int32_t>(params.get(), "dimensions", info.dimensions, comm, tmp);
    }
    {
      const auto particles = h5::create_group(file.get(), "particles", tmp);
      for (const auto &s : species)
        bytes += create_species(particles.get(), s, info, comm, tmp, jobs);
    }
    for (const auto &a : arrays) {
      // Groups on the way (collective), the size from rank 0 (others may pass no values).
      hid_t loc = file.get();
      std::vector<h5::Group> groups;
      std::size_t from = 0;
      for (std::size_t slash; (slash = a.path.find('/', from)) != std::string::npos;
           from = slash + 1) {
        const std::string g = a.path.substr(0, slash);
        groups.push_back(path_exists(file.get(), g) ? h5::open_group(file.get(), g, tmp)
                                                    : h5::create_group(file.get(), g, tmp));
        loc = groups.back().get();
      }
      std::uint64_t n = a.values.size();
      MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
      const hsize_t dims[1] = {n};
      small_dataset(loc, a.path.substr(from), H5T_NATIVE_DOUBLE, dims, a.values.data(), comm, tmp);
    }
    // Closing is where the last metadata reaches the file: check it (not the destructor).
    h5::check(H5Fclose(file.release()), tmp, "close file");
  }
  // The particle rows: each rank its own byte ranges, straight to the disk (HDF5 allocated
  // the datasets contiguously at creation and wrote no fill values), then synced.
  int failed_rows = 0;
  std::string rows_error;
  try {
    for (const RowJob &job : jobs)
      write_job(tmp, job);
  } catch (const Error &e) {
    failed_rows = 1;
    rows_error = e.what();
  }
  int any_failed = 0;
  MPI_Allreduce(&failed_rows, &any_failed, 1, MPI_INT, MPI_MAX, comm);
  if (any_failed)
    throw Error(ExitCode::other,
                failed_rows ? rows_error : tmp + ": another rank could not write its rows");
  // Only a complete file gets the final name. The data reach the disk before the rename,
  // so not even a power cut leaves a partial checkpoint under the final name.
  int failed = 0;
  std::string why;
  if (rank_of(comm) == 0) {
    std::error_code ec;
    if (!sync_path(tmp, false)) {
      failed = 1;
      why = std::string("fsync failed (") + std::strerror(errno) + ")";
    } else {
      fs::rename(tmp, path, ec);
      if (ec) {
        failed = 1;
        why = "rename from " + tmp + " failed (" + ec.message() + ")";
      } else {
        sync_path(fs::path(path).parent_path().empty() ? std::string(".")
                                                       : fs::path(path).parent_path().string(),
                  true);
      }
    }
  }
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
    throw Error(ExitCode::other,
                path + ": cannot complete checkpoint" + (why.empty() ? "" : ": " + why));
  return bytes;
}

} // namespace

double write_checkpoint(const std::string &path, const CheckpointInfo &info,
                        const std::vector<SpeciesFields> &species, MPI_Comm comm,
                        const std::vector<CheckpointArray> &arrays) {
  try {
    return write_checkpoint_via_tmp(path, info, species, comm, arrays);
  } catch (...) {
    // Never leave a half-written checkpoint-*.h5.tmp behind (every failing rank tries).
    std::error_code ignored;
    fs::remove(path + ".tmp", ignored);
    throw;
  }
}

namespace {

// Opens a checkpoint and reads /parameters (collective); the file stays open in `file`.
CheckpointInfo open_checkpoint(const std::string &path, MPI_Comm comm, h5::File &file) {
  h5::silence_errors();
  std::error_code ec;
  if (!fs::exists(path, ec))
    refuse(path, "cannot open checkpoint (no such file); allowed: a checkpoint-*.h5 file or a "
                 "directory holding one");
  if (!fs::is_regular_file(path, ec))
    refuse(path, "cannot open checkpoint (not a regular file); allowed: a checkpoint-*.h5 file "
                 "or a directory holding one");
  const auto size = fs::file_size(path, ec);
  {
    // Our files carry the HDF5 signature at offset 0 (no user block).
    static const char signature[8] = {'\211', 'H', 'D', 'F', '\r', '\n', '\032', '\n'};
    char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    if (!in)
      refuse(path, std::string("cannot open checkpoint (") + std::strerror(errno) + ")");
    in.read(head, 8);
    if (in.gcount() != 8 || std::memcmp(head, signature, 8) != 0)
      refuse(path, "not an HDF5 file (found no HDF5 signature in its " + std::to_string(size) +
                       " bytes); allowed: a checkpoint-*.h5 written by narrows run");
  }
  const auto fapl = mpio_fapl(comm, path);
  file = h5::File(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()));
  if (!file) {
    const std::string err = hdf5_error_text();
    if (err.find("truncated") != std::string::npos)
      refuse(path, "truncated HDF5 file (" + std::to_string(size) +
                       " bytes; the writer did not finish); allowed: a complete checkpoint");
    refuse(path,
           "damaged HDF5 file, HDF5 cannot open it (" + err + "); allowed: a complete checkpoint");
  }
  const hid_t f = file.get();
  if (!has_checksums(f) && rank_of(comm) == 0)
    std::fprintf(stderr,
                 "warning: %s carries no checksums (written by a narrows before they existed); "
                 "its data are accepted unverified\n",
                 path.c_str());

  CheckpointInfo info;
  const auto version = read_scalar<std::int64_t>(f, "/parameters/format_version", path, false);
  if (version != checkpoint_format_version)
    refuse(path, "/parameters/format_version = " + std::to_string(version) +
                     "; allowed: " + std::to_string(checkpoint_format_version) +
                     " (the format this narrows " NARROWS_VERSION " reads)");
  read_scalar<std::int64_t>(f, "/parameters/format_version", path); // its checksum
  info.scene_text = read_string(f, "/parameters/scene", path);
  if (path_exists(f, "/parameters/canonical_scene"))
    info.canonical_scene = read_string(f, "/parameters/canonical_scene", path);
  info.step = read_scalar<std::int64_t>(f, "/parameters/step", path);
  info.time = read_scalar<double>(f, "/parameters/time", path);
  info.seed = read_scalar<std::uint64_t>(f, "/parameters/seed", path);
  info.dimensions = read_scalar<std::int32_t>(f, "/parameters/dimensions", path);
  // Checkpoint names hold the step in 10 digits (checkpoint_path, list_checkpoints).
  if (info.step < 0 || info.step > max_checkpoint_step)
    refuse(path, "/parameters/step = " + std::to_string(info.step) + "; allowed: 0 to " +
                     std::to_string(max_checkpoint_step));
  if (info.dimensions < 1 || info.dimensions > 3)
    refuse(path,
           "/parameters/dimensions = " + std::to_string(info.dimensions) + "; allowed: 1, 2 or 3");
  if (!(std::isfinite(info.time) && info.time >= 0.0))
    refuse(path, "/parameters/time = " + number_text(info.time) + "; allowed: a finite time >= 0");
  return info;
}

} // namespace

CheckpointInfo read_checkpoint_header(const std::string &path, MPI_Comm comm) {
  h5::File file;
  return open_checkpoint(path, comm, file);
}

CheckpointInfo read_checkpoint_info(const std::string &path, MPI_Comm comm) {
  h5::File file;
  CheckpointInfo info = open_checkpoint(path, comm, file);
  if (info.dimensions == 1)
    refuse(path, "a checkpoint of a kmc run; allowed: a checkpoint of an mpcd run");
  const hid_t f = file.get();
  const std::string pos = "/particles/fluid/position/value",
                    vel = "/particles/fluid/velocity/value", ids = "/particles/fluid/id/value",
                    edges = "/particles/fluid/box/edges";
  const auto p_shape = shape_of(open_required(f, pos, path).get(), path);
  const auto v_shape = shape_of(open_required(f, vel, path).get(), path);
  const auto i_shape = shape_of(open_required(f, ids, path).get(), path);
  if (p_shape.size() != 2 || (p_shape[1] != 2 && p_shape[1] != 3))
    refuse(path, pos + " has shape " + shape_text(p_shape) + "; allowed: [N][2] or [N][3]");
  if (p_shape[1] != static_cast<hsize_t>(info.dimensions))
    refuse(path, pos + " has shape " + shape_text(p_shape) + " but /parameters/dimensions = " +
                     std::to_string(info.dimensions) + "; allowed: [N][dimensions]");
  if (v_shape != p_shape)
    refuse(path, vel + " has shape " + shape_text(v_shape) + ", " + pos + " has " +
                     shape_text(p_shape) + "; allowed: the same shape");
  if (i_shape.size() != 1 || i_shape[0] != p_shape[0])
    refuse(path, "particle count mismatch: " + ids + " has shape " + shape_text(i_shape) + ", " +
                     pos + " has " + shape_text(p_shape) + "; allowed: one id per particle ([" +
                     std::to_string(p_shape[0]) + "])");
  info.fluid_particles = p_shape[0];
  info.box = read_edges(f, edges, info.dimensions, path);
  (void)comm;
  return info;
}

std::vector<double> read_checkpoint_array(const std::string &path, const std::string &name,
                                          std::size_t size, MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  const auto d = open_required(file.get(), "/" + name, path);
  const auto shape = shape_of(d.get(), path);
  if (shape != std::vector<hsize_t>{size})
    refuse(path, "/" + name + " has shape " + shape_text(shape) + "; allowed: [" +
                     std::to_string(size) + "] (what the scene needs)");
  std::vector<double> v(size);
  if (H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    damaged(path, "/" + name);
  verify_checksum(stored_checksum(file.get(), d.get(), "/" + name, path),
                  bytes_hash(v.data(), 8 * size), "/" + name, path);
  for (std::size_t i = 0; i < size; ++i)
    if (!std::isfinite(v[i]))
      refuse(path, "/" + name + " row " + std::to_string(i) + " = " + number_text(v[i]) +
                       "; allowed: a finite number");
  return v;
}

std::array<double, 3> read_box_edges(const std::string &path, const std::string &species, int dim,
                                     MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  return read_edges(file.get(), "/particles/" + species + "/box/edges", dim, path);
}

std::uint64_t species_rows(const std::string &path, const SpeciesFields &s, MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  const std::string first_field =
      "/particles/" + s.name + "/" +
      (!s.vectors.empty() ? s.vectors.front().first : s.words.front().first) + "/value";
  return shape_of(open_required(file.get(), first_field, path).get(), path).at(0);
}

namespace {

// One stored field of a species: its dataset, its width (components per row) and whether it
// holds words (uint64) or doubles.
struct StoredField {
  std::string dataset;
  int width = 1;
  bool words = false;
  bool vector = false;
};

std::vector<StoredField> stored_fields(const SpeciesFields &s) {
  const std::string base = "/particles/" + s.name + "/";
  std::vector<StoredField> out;
  for (const auto &v : s.vectors)
    out.push_back({base + v.first + "/value", s.dim, false, true});
  for (const auto &w : s.words)
    out.push_back({base + w.first + "/value", 1, true, false});
  for (const auto &c : s.scalars)
    out.push_back({base + c.first + "/value", 1, false, false});
  return out;
}

// The checksum of a whole row dataset, read in blocks by rank (collective), whatever its row
// count: a field of the wrong length is still verified (issue 35: a partner_id with one row more
// was never checked).
void verify_whole_dataset(hid_t file, const StoredField &f, const std::vector<hsize_t> &shape,
                          MPI_Comm comm, const std::string &path) {
  const auto d = open_required(file, f.dataset, path);
  const std::uint64_t rows = shape.empty() ? 0 : shape[0];
  const int width = shape.size() == 2 ? static_cast<int>(shape[1]) : 1;
  if (shape.empty() || shape.size() > 2 || width < 1 || width > 3)
    return; // not a row dataset: refused by its shape
  const auto r = static_cast<std::uint64_t>(rank_of(comm));
  const auto p = static_cast<std::uint64_t>(size_of(comm));
  const std::uint64_t first = rows * r / p, n = rows * (r + 1) / p - first;
  std::uint64_t local = 0;
  if (f.words)
    local = read_rows<std::uint64_t>(
        d.get(), first, n, width, comm, [](std::uint64_t *, std::size_t, std::size_t) {}, path,
        f.dataset);
  else
    local = read_rows<double>(
        d.get(), first, n, width, comm, [](double *, std::size_t, std::size_t) {}, path, f.dataset);
  std::uint64_t sum = 0;
  MPI_Allreduce(&local, &sum, 1, MPI_UINT64_T, MPI_SUM, comm);
  verify_checksum(stored_checksum(file, d.get(), f.dataset, path), sum, f.dataset, path);
}

// Every field of the species present, of its shape ([N][d] or [N]) and, with `exact`, of one row
// count N; else at least `need` rows. Collective agreement: every rank reads the same metadata
// and `need` is the largest of all ranks, so a short field is refused on every rank before any
// rank reads a row (issue 35: a short contact field deadlocked 2 and 3 ranks). Before a row
// count is refused, the checksum of every field is verified (a damaged file is named as such).
void check_stored_shapes(hid_t file, const SpeciesFields &s, bool exact, std::uint64_t need,
                         MPI_Comm comm, const std::string &path) {
  const auto fields = stored_fields(s);
  std::vector<std::vector<hsize_t>> shapes;
  for (const auto &f : fields)
    shapes.push_back(shape_of(open_required(file, f.dataset, path).get(), path));
  std::string line;
  // The row count most fields have (the first field's on a tie): the odd field is named.
  std::uint64_t rows0 = shapes.empty() || shapes[0].empty() ? 0 : shapes[0][0];
  std::size_t most = 0;
  for (const auto &a : shapes) {
    const std::size_t same =
        static_cast<std::size_t>(std::count_if(shapes.begin(), shapes.end(), [&](const auto &b) {
          return !a.empty() && !b.empty() && b[0] == a[0];
        }));
    if (!a.empty() && same > most) {
      most = same;
      rows0 = a[0];
    }
  }
  for (std::size_t i = 0; i < fields.size() && line.empty(); ++i) {
    const auto &f = fields[i];
    const auto &shape = shapes[i];
    const bool shape_ok = f.vector ? shape.size() == 2 && shape[1] == static_cast<hsize_t>(f.width)
                                   : shape.size() == 1;
    if (!shape_ok)
      line = f.dataset + " has shape " + shape_text(shape) + "; allowed: " +
             (f.vector ? "[N][" + std::to_string(f.width) + "] (one row of " +
                             std::to_string(f.width) + " components per particle)"
                       : std::string("[N] (one value per particle)"));
    else if (exact && shape[0] != rows0)
      line = f.dataset + " has " + std::to_string(shape[0]) +
             " rows, the other fields of /particles/" + s.name + " " + std::to_string(rows0) +
             "; allowed: the same number of rows in every field of the species";
    else if (!exact && shape[0] < need)
      line = f.dataset + " has " + std::to_string(shape[0]) + " rows; allowed: at least " +
             std::to_string(need) + " (the rows this run reads)";
  }
  if (line.empty())
    return;
  for (std::size_t i = 0; i < fields.size(); ++i)
    verify_whole_dataset(file, fields[i], shapes[i], comm, path);
  refuse(path, line);
}

// The step and time of each field's group (/particles/<species>/<field>/{step, time}) must be
// those of /parameters: a state written at one step.
void check_field_steps(hid_t file, const SpeciesFields &s, const std::string &path) {
  const auto step = read_scalar<std::int64_t>(file, "/parameters/step", path);
  const auto time = read_scalar<double>(file, "/parameters/time", path);
  for (const auto &f : stored_fields(s)) {
    const std::string group = f.dataset.substr(0, f.dataset.rfind('/'));
    if (path_exists(file, group + "/step")) {
      const auto v = read_scalar<std::int64_t>(file, group + "/step", path);
      if (v != step)
        refuse(path, group + "/step = " + std::to_string(v) + " but /parameters/step = " +
                         std::to_string(step) + "; allowed: the same step (one state)");
    }
    if (path_exists(file, group + "/time")) {
      const auto v = read_scalar<double>(file, group + "/time", path);
      if (v != time)
        refuse(path, group + "/time = " + number_text(v) + " but /parameters/time = " +
                         number_text(time) + "; allowed: the same time (one state)");
    }
  }
}

} // namespace

void read_species(const std::string &path, SpeciesFields &s, MPI_Comm comm) {
  {
    h5::silence_errors();
    const h5::File file = open_readable(path, comm);
    check_stored_shapes(file.get(), s, true, 0, comm, path);
  }
  const auto total = species_rows(path, s, comm);
  const auto r = static_cast<std::uint64_t>(rank_of(comm));
  const auto p = static_cast<std::uint64_t>(size_of(comm));
  read_species_rows(path, s, total * r / p, total * (r + 1) / p - total * r / p, comm);
}

void read_species_rows(const std::string &path, SpeciesFields &s, std::uint64_t first,
                       std::uint64_t n, MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  const std::string base = "/particles/" + s.name + "/";
  {
    const std::uint64_t end = first + n;
    std::uint64_t need = 0;
    MPI_Allreduce(&end, &need, 1, MPI_UINT64_T, MPI_MAX, comm);
    check_stored_shapes(file.get(), s, false, need, comm, path);
    check_field_steps(file.get(), s, path);
  }
  if (path_exists(file.get(), base + "box/edges"))
    verify_small(file.get(), base + "box/edges", path);
  // The checksum covers the whole dataset: verified when the ranks' rows together are all of
  // it (every reader reads a partition of the rows), the same outcome on every rank.
  const auto verify = [&](const h5::Dataset &d, const std::string &name, std::uint64_t local) {
    const std::uint64_t mine[2] = {n, local};
    std::uint64_t all[2] = {0, 0};
    MPI_Allreduce(mine, all, 2, MPI_UINT64_T, MPI_SUM, comm);
    const auto shape = shape_of(d.get(), path);
    if (!shape.empty() && all[0] == shape[0])
      verify_checksum(stored_checksum(file.get(), d.get(), name, path), all[1], name, path);
    const std::string group = name.substr(0, name.rfind('/'));
    for (const char *small : {"/step", "/time"})
      if (path_exists(file.get(), group + small))
        verify_small(file.get(), group + small, path);
  };
  for (auto &[name, comp] : s.vectors) {
    const std::string dname = base + name + "/value";
    const auto d = open_required(file.get(), dname, path);
    for (int k = 0; k < s.dim; ++k)
      comp[k]->resize(n);
    const int dim = s.dim;
    const auto sum = read_rows<double>(
        d.get(), first, n, dim, comm,
        [&comp, dim](double *buf, std::size_t at, std::size_t count) {
          for (int k = 0; k < dim; ++k) {
            double *dst = comp[k]->data() + at;
            for (std::size_t i = 0; i < count; ++i)
              dst[i] = buf[i * dim + k];
          }
        },
        path, dname);
    verify(d, dname, sum);
  }
  for (auto &[name, words] : s.words) {
    const std::string dname = base + name + "/value";
    const auto d = open_required(file.get(), dname, path);
    words->resize(n);
    const auto sum = read_rows<std::uint64_t>(
        d.get(), first, n, 1, comm,
        [words](std::uint64_t *buf, std::size_t at, std::size_t count) {
          std::copy_n(buf, count, words->data() + at);
        },
        path, dname);
    verify(d, dname, sum);
  }
  for (auto &[name, values] : s.scalars) {
    const std::string dname = base + name + "/value";
    const auto d = open_required(file.get(), dname, path);
    values->resize(n);
    const auto sum = read_rows<double>(
        d.get(), first, n, 1, comm,
        [values](double *buf, std::size_t at, std::size_t count) {
          std::copy_n(buf, count, values->data() + at);
        },
        path, dname);
    verify(d, dname, sum);
  }
}

bool has_checkpoint_array(const std::string &path, const std::string &name, MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  return path_exists(file.get(), "/" + name);
}

bool has_species_field(const std::string &path, const std::string &species,
                       const std::string &field, MPI_Comm comm) {
  h5::silence_errors();
  const h5::File file = open_readable(path, comm);
  return path_exists(file.get(), "/particles/" + species + "/" + field + "/value");
}

// ---- files of a run directory ------------------------------------------------------------

std::string checkpoint_path(const std::string &dir, std::int64_t step) {
  char name[40];
  std::snprintf(name, sizeof name, "checkpoint-%010lld.h5", static_cast<long long>(step));
  return (fs::path(dir) / name).string();
}

std::vector<std::string> list_checkpoints(const std::string &dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() == 24 && name.rfind("checkpoint-", 0) == 0 && name.compare(21, 3, ".h5") == 0 &&
        std::all_of(name.begin() + 11, name.begin() + 21,
                    [](char c) { return c >= '0' && c <= '9'; }))
      out.push_back(it->path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string resolve_restart(const std::string &arg) {
  std::error_code ec;
  if (!fs::is_directory(arg, ec))
    return arg;
  const auto all = list_checkpoints(arg);
  if (all.empty())
    throw input_error("--restart " + arg +
                      ": no checkpoint-<step>.h5 in this directory; allowed: a checkpoint file "
                      "or a directory holding one");
  return all.back();
}

void prune_checkpoints(const std::string &dir, int keep) {
  const auto all = list_checkpoints(dir);
  std::error_code ec;
  for (std::size_t i = 0; i + static_cast<std::size_t>(std::max(keep, 1)) < all.size(); ++i)
    fs::remove(all[i], ec);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("checkpoint-", 0) == 0 && name.size() > 4 &&
        name.compare(name.size() - 7, 7, ".h5.tmp") == 0) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

} // namespace narrows::io
