// Thin RAII layer over the HDF5 C API: owning handles for hid_t, checked calls that turn a
// failure into narrows::Error, and a few helpers for attributes and small datasets.
#pragma once

#include "narrows/core/error.hpp"

#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace narrows::io::h5 {

// Turns off HDF5's automatic printing of its error stack (we report errors ourselves).
// Idempotent; every helper below that opens or creates a file calls it.
void silence_errors();

// Throws Error(ExitCode::other, "<where>: HDF5 <what> failed") when an HDF5 call fails.
// `where` is the file path (the user-facing context), `what` the operation.
[[noreturn]] void fail(const std::string &where, const std::string &what);
inline hid_t check_id(hid_t id, const std::string &where, const std::string &what) {
  if (id < 0)
    fail(where, what);
  return id;
}
inline herr_t check(herr_t status, const std::string &where, const std::string &what) {
  if (status < 0)
    fail(where, what);
  return status;
}

// Owns one HDF5 identifier and closes it with Close on destruction. Movable, not copyable.
template <herr_t (*Close)(hid_t)> class Handle {
public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  // Checked construction: throws if `id` is negative (the call that produced it failed).
  Handle(hid_t id, const std::string &where, const std::string &what)
      : id_(check_id(id, where, what)) {}
  ~Handle() { reset(); }
  Handle(Handle &&other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Handle &operator=(Handle &&other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  hid_t release() { return std::exchange(id_, H5I_INVALID_HID); }
  // Errors on close cannot be reported from a destructor; callers that care (a checkpoint
  // that must be complete before it is renamed) flush the file first.
  void reset() noexcept {
    if (id_ >= 0)
      Close(id_);
    id_ = H5I_INVALID_HID;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
};

using File = Handle<H5Fclose>;
using Group = Handle<H5Gclose>;
using Dataset = Handle<H5Dclose>;
using Dataspace = Handle<H5Sclose>;
using Datatype = Handle<H5Tclose>;
using PropList = Handle<H5Pclose>;
using Attribute = Handle<H5Aclose>;

// Memory type of a C++ arithmetic type.
template <class T> hid_t native_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_NATIVE_FLOAT;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_NATIVE_INT32;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return H5T_NATIVE_UINT32;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_NATIVE_INT64;
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return H5T_NATIVE_UINT64;
  else
    static_assert(!sizeof(T), "no HDF5 type for this C++ type");
}

// Files. `fapl` is a file-access property list (H5P_DEFAULT for serial; an mpio one for
// collective I/O).
File create_file(const std::string &path, hid_t fapl = H5P_DEFAULT); // truncates
File open_file(const std::string &path, unsigned flags = H5F_ACC_RDONLY, hid_t fapl = H5P_DEFAULT);
void flush(const File &file, const std::string &where);

Group create_group(hid_t loc, const std::string &name, const std::string &where);
Group open_group(hid_t loc, const std::string &name, const std::string &where);

Dataspace scalar_dataspace(const std::string &where);
// maxdims empty: fixed size; otherwise same rank as dims (H5S_UNLIMITED allowed).
Dataspace simple_dataspace(std::span<const hsize_t> dims, std::span<const hsize_t> maxdims,
                           const std::string &where);

// Variable-length UTF-8 string type (shows up as str in h5py).
Datatype string_type(const std::string &where);

// Attributes on any object (file, group, dataset).
void write_string_attribute(hid_t obj, const std::string &name, const std::string &value,
                            const std::string &where);
void write_attribute(hid_t obj, const std::string &name, hid_t type, std::span<const hsize_t> dims,
                     const void *data, const std::string &where);
template <class T>
void write_attribute(hid_t obj, const std::string &name, std::span<const T> values,
                     const std::string &where) {
  const hsize_t n = values.size();
  write_attribute(obj, name, native_type<T>(), std::span<const hsize_t>(&n, 1), values.data(),
                  where);
}

// Small contiguous datasets written in one go (serial, or identical on all ranks).
// dims empty: a scalar dataset.
void write_dataset(hid_t loc, const std::string &name, hid_t type, std::span<const hsize_t> dims,
                   const void *data, const std::string &where);
void write_string_dataset(hid_t loc, const std::string &name, const std::string &value,
                          const std::string &where);
template <class T>
void write_dataset(hid_t loc, const std::string &name, std::span<const T> values,
                   const std::string &where) {
  const hsize_t n = values.size();
  write_dataset(loc, name, native_type<T>(), std::span<const hsize_t>(&n, 1), values.data(), where);
}
template <class T>
void write_scalar(hid_t loc, const std::string &name, T value, const std::string &where) {
  write_dataset(loc, name, native_type<T>(), std::span<const hsize_t>(), &value, where);
}

// Time series: an empty dataset of shape [0][sample_shape...], chunked, unlimited along axis 0,
// and the append of one sample as row `row` (the dataset grows to row + 1 rows).
Dataset create_series(hid_t group, const std::string &name, hid_t type,
                      const std::vector<hsize_t> &sample_shape, const std::string &where);
void write_row(const Dataset &dset, hsize_t row, hid_t type,
               const std::vector<hsize_t> &sample_shape, const void *data, const std::string &where,
               const std::string &name);
// The same for n rows from row `first` on (the dataset grows to first + n rows; n may be 0).
void write_rows(const Dataset &dset, hsize_t first, hsize_t n, hid_t type,
                const std::vector<hsize_t> &sample_shape, const void *data,
                const std::string &where, const std::string &name);

// The H5MD header every narrows output file starts with: /h5md (version = [1, 1], creator
// name and version) and /parameters/scene; returns the /parameters group for more entries.
Group write_h5md_header(hid_t file, const std::string &scene_text, const std::string &where);

} // namespace narrows::io::h5
