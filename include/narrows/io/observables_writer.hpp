// observables.h5: H5MD-style time series /observables/<name>/{step, time, value[, bins]}.
#pragma once

#include "narrows/io/hdf5.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace narrows::io {

// Serial writer of the observables file; only rank 0 creates one. Every series is a set of
// chunked datasets with an unlimited first (time) dimension, extended by one row per append.
// Errors throw narrows::Error (ExitCode::other) naming the file.
class ObservablesWriter {
public:
  // Creates (truncates) `path`; writes /h5md (version = [1, 1], /h5md/creator with name and
  // version) and /parameters/scene (the scene text).
  ObservablesWriter(const std::string &path, const std::string &scene_text);

  // One sample of a scalar: value shape [T].
  void append_scalar(const std::string &name, std::int64_t step, double time, double value);
  // One sample of a vector of k >= 1 components: value shape [T][k].
  void append_vector(const std::string &name, std::int64_t step, double time,
                     std::span<const double> v);
  // One sample of a profile over bins.size() bins, `values` row-major [bins][components]:
  // value shape [T][bins][components], or [T][bins] when components == 1. The bin centres
  // are stored once, at the first append, in /observables/<name>/bins.
  void append_profile(const std::string &name, std::int64_t step, double time,
                      std::span<const double> bins, std::span<const double> values,
                      std::size_t components);

  // One sample of several profiles over the same bins, each its own series: datasets
  // /observables/<name>/<field> of shape [T][bins] (no `value`), beside step, time and bins.
  // Every sample names the same fields in the same order.
  void append_profiles(const std::string &name, std::int64_t step, double time,
                       std::span<const double> bins,
                       const std::vector<std::pair<std::string, std::span<const double>>> &fields);

  // One sample of a field of any shape (row-major `values`): value shape [T][shape...].
  void append_field(const std::string &name, std::int64_t step, double time,
                    const std::vector<hsize_t> &shape, std::span<const double> values);

  // A dataset of one row per sample beside value, in the same group (append_field below).
  struct Beside {
    std::string key;
    std::vector<hsize_t> shape; // of one sample ({} for a scalar)
    std::span<const double> values;
  };
  // One sample of a field (value [T][shape...]) with more datasets of one row per sample beside
  // it ([T][their shape...], marked with the attribute per_sample = 1, so that readers join them
  // over a restart chain as they join value), and at the first append the 1-D `axes` (e.g.
  // bins). Every sample of a name must have the same keys and shapes. An empty `shape` is a
  // scalar sample: value [T].
  void append_field(const std::string &name, std::int64_t step, double time,
                    const std::vector<hsize_t> &shape, std::span<const double> values,
                    const std::vector<Beside> &beside,
                    const std::vector<std::pair<std::string, std::vector<double>>> &axes);

  // A result of the whole run rather than a sample (e.g. a correlation function over lags):
  // /observables/<name>/{step, time} scalars, value of shape [n], and beside it the named
  // 1-D datasets of `beside` (e.g. lags, error). Written once per name. With `shape`, value
  // (and the datasets of `beside` named in `shaped`) have that shape (row-major) instead.
  void write_result(const std::string &name, std::int64_t step, double time,
                    std::span<const double> value,
                    const std::vector<std::pair<std::string, std::vector<double>>> &beside,
                    const std::vector<hsize_t> &shape = {},
                    const std::vector<std::string> &shaped = {});

  // Attributes of the group /parameters/<name> (created on first use): numbers and strings,
  // e.g. the resolved parameters of a model that the scene only names (a preset, a fit file).
  void write_parameters(const std::string &name,
                        const std::vector<std::pair<std::string, double>> &numbers,
                        const std::vector<std::pair<std::string, std::string>> &strings);

  // H5Fflush: what was appended so far survives a crash of the run.
  void flush();

  const std::string &path() const { return path_; }

private:
  enum class Kind { scalar, vector, profile, field, profiles };
  struct Series {
    Kind kind;
    std::vector<hsize_t> sample_shape; // shape of one sample (value without the T axis)
    hsize_t samples = 0;
    h5::Dataset step, time, value;
    std::vector<std::pair<std::vector<hsize_t>, h5::Dataset>> beside; // (append_field's)
    // profiles: the named datasets instead of value
    std::vector<std::pair<std::string, h5::Dataset>> fields = {};
  };

  Series &series(const std::string &name, Kind kind, std::vector<hsize_t> sample_shape,
                 std::span<const double> bins);
  void append(Series &s, const std::string &name, std::int64_t step, double time,
              const double *value);

  std::string path_;
  h5::File file_;
  h5::Group observables_, parameters_;
  std::map<std::string, Series> series_;
};

} // namespace narrows::io
