// ObservablesWriter: appends samples to extendible, chunked HDF5 time series.
#include "narrows/io/observables_writer.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace narrows::io {

namespace {

std::string shape_string(const std::vector<hsize_t> &shape) {
  std::string s = "[T]";
  for (const hsize_t n : shape)
    s += "[" + std::to_string(n) + "]";
  return s;
}

} // namespace

ObservablesWriter::ObservablesWriter(const std::string &path, const std::string &scene_text)
    : path_(path), file_(h5::create_file(path)) {
  parameters_ = h5::write_h5md_header(file_.get(), scene_text, path_);
  observables_ = h5::create_group(file_.get(), "observables", path_);
}

ObservablesWriter::Series &ObservablesWriter::series(const std::string &name, Kind kind,
                                                     std::vector<hsize_t> sample_shape,
                                                     std::span<const double> bins) {
  static constexpr const char *kind_names[] = {"scalar", "vector", "profile", "field",
                                               "set of profiles"};
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
  Series s{kind, std::move(sample_shape), 0, {}, {}, {}, {}};
  s.step = h5::create_series(group.get(), "step", H5T_STD_I64LE, {}, path_);
  s.time = h5::create_series(group.get(), "time", H5T_IEEE_F64LE, {}, path_);
  if (kind != Kind::profiles)
    s.value = h5::create_series(group.get(), "value", H5T_IEEE_F64LE, s.sample_shape, path_);
  if (kind == Kind::profile || kind == Kind::profiles)
    h5::write_dataset<double>(group.get(), "bins", bins, path_);
  return series_.emplace(name, std::move(s)).first->second;
}

void ObservablesWriter::append(Series &s, const std::string &name, std::int64_t step, double time,
                               const double *value) {
  // The sample count advances only when all three rows are written; a retry after a failure
  // rewrites the same row.
  const std::string prefix = "/observables/" + name + "/";
  h5::write_row(s.step, s.samples, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
  h5::write_row(s.time, s.samples, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
  h5::write_row(s.value, s.samples, H5T_NATIVE_DOUBLE, s.sample_shape, value, path_,
                prefix + "value");
  ++s.samples;
}

void ObservablesWriter::write_parameters(
    const std::string &name, const std::vector<std::pair<std::string, double>> &numbers,
    const std::vector<std::pair<std::string, std::string>> &strings) {
  const h5::Group group = h5::create_group(parameters_.get(), name, path_);
  for (const auto &[key, x] : numbers)
    h5::write_attribute<double>(group.get(), key, std::span<const double>(&x, 1), path_);
  for (const auto &[key, text] : strings)
    h5::write_string_attribute(group.get(), key, text, path_);
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

void ObservablesWriter::append_profiles(
    const std::string &name, std::int64_t step, double time, std::span<const double> bins,
    const std::vector<std::pair<std::string, std::span<const double>>> &fields) {
  for (const auto &[field, values] : fields)
    if (bins.empty() || values.size() != bins.size() || field.empty() ||
        field.find('/') != std::string::npos || field == "step" || field == "time" ||
        field == "bins")
      throw Error(ExitCode::other, path_ + ": profile '" + name + "/" + field + "' has " +
                                       std::to_string(values.size()) + " values for " +
                                       std::to_string(bins.size()) + " bins (or a bad name)");
  Series &s = series(name, Kind::profiles, {bins.size()}, bins);
  if (s.fields.empty()) {
    const h5::Group group = h5::open_group(observables_.get(), name, path_);
    for (const auto &f : fields)
      s.fields.emplace_back(
          f.first, h5::create_series(group.get(), f.first, H5T_IEEE_F64LE, s.sample_shape, path_));
  }
  bool same = s.fields.size() == fields.size();
  for (std::size_t j = 0; same && j < fields.size(); ++j)
    same = s.fields[j].first == fields[j].first;
  if (!same)
    throw Error(ExitCode::other,
                path_ + ": profiles '" + name + "' were written with other fields before");
  // As append(): the sample count advances only when every row is written.
  const std::string prefix = "/observables/" + name + "/";
  h5::write_row(s.step, s.samples, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
  h5::write_row(s.time, s.samples, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
  for (std::size_t j = 0; j < fields.size(); ++j)
    h5::write_row(s.fields[j].second, s.samples, H5T_NATIVE_DOUBLE, s.sample_shape,
                  fields[j].second.data(), path_, prefix + fields[j].first);
  ++s.samples;
}

void ObservablesWriter::append_field(const std::string &name, std::int64_t step, double time,
                                     const std::vector<hsize_t> &shape,
                                     std::span<const double> values) {
  hsize_t n = 1;
  for (const hsize_t k : shape)
    n *= k;
  if (shape.empty() || n == 0 || values.size() != n)
    throw Error(ExitCode::other, path_ + ": field '" + name + "' has " +
                                     std::to_string(values.size()) + " values for shape " +
                                     shape_string(shape));
  append(series(name, Kind::field, shape, {}), name, step, time, values.data());
}

void ObservablesWriter::append_field(
    const std::string &name, std::int64_t step, double time, const std::vector<hsize_t> &shape,
    std::span<const double> values, const std::vector<Beside> &beside,
    const std::vector<std::pair<std::string, std::vector<double>>> &axes) {
  const auto elements = [](const std::vector<hsize_t> &sh) {
    hsize_t n = 1;
    for (const hsize_t k : sh)
      n *= k;
    return n;
  };
  for (const Beside &b : beside)
    if (b.key.empty() || b.key.find('/') != std::string::npos || b.key == "step" ||
        b.key == "time" || b.key == "value" || b.values.size() != elements(b.shape))
      throw Error(ExitCode::other, path_ + ": field '" + name + "': dataset '" + b.key +
                                       "' beside value has " + std::to_string(b.values.size()) +
                                       " values for shape " + shape_string(b.shape));
  if (elements(shape) == 0 || values.size() != elements(shape))
    throw Error(ExitCode::other, path_ + ": field '" + name + "' has " +
                                     std::to_string(values.size()) + " values for shape " +
                                     shape_string(shape));
  const bool fresh = series_.count(name) == 0;
  Series &s = series(name, Kind::field, shape, {});
  if (fresh) {
    const h5::Group group = h5::open_group(observables_.get(), name, path_);
    for (const Beside &b : beside) {
      h5::Dataset d = h5::create_series(group.get(), b.key, H5T_IEEE_F64LE, b.shape, path_);
      const std::array<std::int32_t, 1> one{1};
      h5::write_attribute<std::int32_t>(d.get(), "per_sample", one, path_);
      s.beside.emplace_back(b.shape, std::move(d));
    }
    for (const auto &[key, data] : axes)
      h5::write_dataset<double>(group.get(), key, data, path_);
  }
  if (s.beside.size() != beside.size())
    throw Error(ExitCode::other, path_ + ": field '" + name + "' was written with " +
                                     std::to_string(s.beside.size()) +
                                     " datasets beside value, now " +
                                     std::to_string(beside.size()));
  for (std::size_t j = 0; j < beside.size(); ++j)
    if (s.beside[j].first != beside[j].shape)
      throw Error(ExitCode::other, path_ + ": field '" + name + "': dataset '" + beside[j].key +
                                       "' was of shape " + shape_string(s.beside[j].first) +
                                       ", now " + shape_string(beside[j].shape));
  // The datasets beside value first: the sample counts only once value is written too.
  const std::string prefix = "/observables/" + name + "/";
  for (std::size_t j = 0; j < beside.size(); ++j)
    h5::write_row(s.beside[j].second, s.samples, H5T_NATIVE_DOUBLE, beside[j].shape,
                  beside[j].values.data(), path_, prefix + beside[j].key);
  append(s, name, step, time, values.data());
}

void ObservablesWriter::write_result(
    const std::string &name, std::int64_t step, double time, std::span<const double> value,
    const std::vector<std::pair<std::string, std::vector<double>>> &beside,
    const std::vector<hsize_t> &shape, const std::vector<std::string> &shaped) {
  if (name.empty() || name.find('/') != std::string::npos || series_.count(name) != 0)
    throw Error(ExitCode::other, path_ + ": invalid or repeated observable name '" + name + "'");
  hsize_t elements = 1;
  for (const hsize_t n : shape)
    elements *= n;
  if (!shape.empty() && elements != value.size())
    throw Error(ExitCode::other, path_ + ": observable '" + name + "' has " +
                                     std::to_string(value.size()) +
                                     " values, not the product of its shape");
  const h5::Group group = h5::create_group(observables_.get(), name, path_);
  h5::write_scalar<std::int64_t>(group.get(), "step", step, path_);
  h5::write_scalar<double>(group.get(), "time", time, path_);
  const auto put = [&](const std::string &key, std::span<const double> data, bool like_value) {
    if (like_value && !shape.empty()) {
      if (data.size() != value.size())
        throw Error(ExitCode::other,
                    path_ + ": observable '" + name + "', " + key + " does not have its shape");
      h5::write_dataset(group.get(), key, h5::native_type<double>(),
                        std::span<const hsize_t>(shape), data.data(), path_);
    } else {
      h5::write_dataset<double>(group.get(), key, data, path_);
    }
  };
  put("value", value, true);
  for (const auto &[key, data] : beside)
    put(key, std::span<const double>(data),
        std::find(shaped.begin(), shaped.end(), key) != shaped.end());
}

void ObservablesWriter::flush() { h5::flush(file_, path_); }

} // namespace narrows::io
