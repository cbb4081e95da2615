// ObservablesWriter: appends samples to extendible, chunked HDF5 time series.
#include "narrows/io/observables_writer.hpp"

#include <algorithm>
#include <array>
#include <utility>

#ifndef NARROWS_VERSION
#define NARROWS_VERSION "dev"
#endif

namespace narrows::io {

namespace {

std::string shape_string(const std::vector<hsize_t> &shape) {
  std::string s = "[T]";
  for (const hsize_t n : shape)
    s += "[" + std::to_string(n) + "]";
  return s;
}

// Rows per chunk: about 32 KiB of doubles per chunk, at most 256 rows, at least one (small
// enough for short runs, large enough that long runs do not drown in chunk metadata).
hsize_t chunk_rows(const std::vector<hsize_t> &sample_shape) {
  hsize_t elements = 1;
  for (const hsize_t n : sample_shape)
    elements *= n;
  return std::clamp<hsize_t>(4096 / elements, 1, 256);
}

// An empty dataset of shape [0][sample_shape...] that can grow without limit along axis 0.
h5::Dataset create_series(hid_t group, const std::string &name, hid_t type,
                          const std::vector<hsize_t> &sample_shape, const std::string &where) {
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{chunk_rows(sample_shape)};
  for (const hsize_t n : sample_shape) {
    dims.push_back(n);
    maxdims.push_back(n);
    chunk.push_back(n);
  }
  const h5::Dataspace space = h5::simple_dataspace(dims, maxdims, where);
  const h5::PropList dcpl(H5Pcreate(H5P_DATASET_CREATE), where, "create property list");
  h5::check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), where,
            "set chunk size of " + name);
  return h5::Dataset(
      H5Dcreate2(group, name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      where, "create dataset " + name);
}

// Grows `dset` to row + 1 rows and writes `data` (one sample) into row `row`.
void write_row(const h5::Dataset &dset, hsize_t row, hid_t type,
               const std::vector<hsize_t> &sample_shape, const void *data, const std::string &where,
               const std::string &name) {
  std::vector<hsize_t> dims{row + 1}, start{row}, count{1};
  for (const hsize_t n : sample_shape) {
    dims.push_back(n);
    start.push_back(0);
    count.push_back(n);
  }
  h5::check(H5Dset_extent(dset.get(), dims.data()), where, "extend dataset " + name);
  const h5::Dataspace file_space(H5Dget_space(dset.get()), where, "get dataspace of " + name);
  h5::check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                count.data(), nullptr),
            where, "select row of " + name);
  const h5::Dataspace mem_space = h5::simple_dataspace(count, {}, where);
  h5::check(H5Dwrite(dset.get(), type, mem_space.get(), file_space.get(), H5P_DEFAULT, data), where,
            "write dataset " + name);
}

} // namespace

ObservablesWriter::ObservablesWriter(const std::string &path, const std::string &scene_text)
    : path_(path), file_(h5::create_file(path)) {
  const h5::Group h5md = h5::create_group(file_.get(), "h5md", path_);
  const std::array<std::int32_t, 2> version{1, 1};
  h5::write_attribute<std::int32_t>(h5md.get(), "version", version, path_);
  const h5::Group creator = h5::create_group(h5md.get(), "creator", path_);
  h5::write_string_attribute(creator.get(), "name", "narrows", path_);
  h5::write_string_attribute(creator.get(), "version", NARROWS_VERSION, path_);

  const h5::Group parameters = h5::create_group(file_.get(), "parameters", path_);
  h5::write_string_dataset(parameters.get(), "scene", scene_text, path_);

  observables_ = h5::create_group(file_.get(), "observables", path_);
}

ObservablesWriter::Series &ObservablesWriter::series(const std::string &name, Kind kind,
                                                     std::vector<hsize_t> sample_shape,
                                                     std::span<const double> bins) {
  static constexpr const char *kind_names[] = {"scalar", "vector", "profile"};
  if (const auto it = series_.find(name); it != series_.end()) {
    Series &s = it->second;
    if (s.kind != kind || s.sample_shape != sample_shape)
      throw Error(ExitCode::other, path_ + ": observable '" + name + "' was written as a " +
                                       kind_names[static_cast<int>(s.kind)] + " of shape " +
                                       shape_string(s.sample_shape) + ", now a " +
                                       kind_names[static_cast<int>(kind)] + " of shape " +
                                       shape_string(sample_shape));
    return s;
  }

  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw Error(ExitCode::other, path_ + ": invalid observable name '" + name + "'");

  const h5::Group group = h5::create_group(observables_.get(), name, path_);
  Series s{kind, std::move(sample_shape), 0, {}, {}, {}};
  s.step = create_series(group.get(), "step", H5T_STD_I64LE, {}, path_);
  s.time = create_series(group.get(), "time", H5T_IEEE_F64LE, {}, path_);
  s.value = create_series(group.get(), "value", H5T_IEEE_F64LE, s.sample_shape, path_);
  if (kind == Kind::profile)
    h5::write_dataset<double>(group.get(), "bins", bins, path_);
  return series_.emplace(name, std::move(s)).first->second;
}

void ObservablesWriter::append(Series &s, const std::string &name, std::int64_t step, double time,
                               const double *value) {
  // The sample count advances only when all three rows are written; a retry after a failure
  // rewrites the same row.
  const std::string prefix = "/observables/" + name + "/";
  write_row(s.step, s.samples, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
  write_row(s.time, s.samples, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
  write_row(s.value, s.samples, H5T_NATIVE_DOUBLE, s.sample_shape, value, path_, prefix + "value");
  ++s.samples;
}

void ObservablesWriter::append_scalar(const std::string &name, std::int64_t step, double time,
                                      double value) {
  append(series(name, Kind::scalar, {}, {}), name, step, time, &value);
}

void ObservablesWriter::append_vector(const std::string &name, std::int64_t step, double time,
                                      std::span<const double> v) {
  if (v.empty())
    throw Error(ExitCode::other, path_ + ": observable '" + name + "' is an empty vector");
  append(series(name, Kind::vector, {v.size()}, {}), name, step, time, v.data());
}

void ObservablesWriter::append_profile(const std::string &name, std::int64_t step, double time,
                                       std::span<const double> bins, std::span<const double> values,
                                       std::size_t components) {
  if (bins.empty() || components == 0 || values.size() != bins.size() * components)
    throw Error(ExitCode::other, path_ + ": profile '" + name + "' has " +
                                     std::to_string(values.size()) + " values for " +
                                     std::to_string(bins.size()) + " bins of " +
                                     std::to_string(components) + " components");
  std::vector<hsize_t> shape{bins.size()};
  if (components > 1)
    shape.push_back(components);
  append(series(name, Kind::profile, std::move(shape), bins), name, step, time, values.data());
}

void ObservablesWriter::flush() { h5::flush(file_, path_); }

} // namespace narrows::io
