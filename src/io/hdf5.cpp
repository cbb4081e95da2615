// The RAII HDF5 layer: checked file/group/dataspace creation and small-write helpers.
#include "narrows/io/hdf5.hpp"

#include <algorithm>
#include <array>

#ifndef NARROWS_VERSION
#define NARROWS_VERSION "dev"
#endif

namespace narrows::io::h5 {

void silence_errors() {
  // Function-local static: runs once, thread-safe, no mutable global.
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

void fail(const std::string &where, const std::string &what) {
  throw Error(ExitCode::other, where + ": HDF5 " + what + " failed");
}

File create_file(const std::string &path, hid_t fapl) {
  silence_errors();
  return File(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), path, "create file");
}

File open_file(const std::string &path, unsigned flags, hid_t fapl) {
  silence_errors();
  return File(H5Fopen(path.c_str(), flags, fapl), path, "open file");
}

void flush(const File &file, const std::string &where) {
  check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), where, "flush");
}

Group create_group(hid_t loc, const std::string &name, const std::string &where) {
  return Group(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), where,
               "create group " + name);
}

Group open_group(hid_t loc, const std::string &name, const std::string &where) {
  return Group(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), where, "open group " + name);
}

Dataspace scalar_dataspace(const std::string &where) {
  return Dataspace(H5Screate(H5S_SCALAR), where, "create dataspace");
}

Dataspace simple_dataspace(std::span<const hsize_t> dims, std::span<const hsize_t> maxdims,
                           const std::string &where) {
  if (dims.empty())
    return scalar_dataspace(where);
  if (!maxdims.empty() && maxdims.size() != dims.size())
    fail(where, "create dataspace (rank of maxdims)");
  return Dataspace(H5Screate_simple(static_cast<int>(dims.size()), dims.data(),
                                    maxdims.empty() ? nullptr : maxdims.data()),
                   where, "create dataspace");
}

Datatype string_type(const std::string &where) {
  Datatype type(H5Tcopy(H5T_C_S1), where, "copy string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), where, "set string size");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), where, "set string charset");
  return type;
}

void write_string_attribute(hid_t obj, const std::string &name, const std::string &value,
                            const std::string &where) {
  const Datatype type = string_type(where);
  const char *text = value.c_str();
  write_attribute(obj, name, type.get(), std::span<const hsize_t>(), &text, where);
}

void write_attribute(hid_t obj, const std::string &name, hid_t type, std::span<const hsize_t> dims,
                     const void *data, const std::string &where) {
  const Dataspace space = simple_dataspace(dims, {}, where);
  const Attribute attr(H5Acreate2(obj, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                       where, "create attribute " + name);
  check(H5Awrite(attr.get(), type, data), where, "write attribute " + name);
}

void write_dataset(hid_t loc, const std::string &name, hid_t type, std::span<const hsize_t> dims,
                   const void *data, const std::string &where) {
  const Dataspace space = simple_dataspace(dims, {}, where);
  const Dataset dset(
      H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      where, "create dataset " + name);
  check(H5Dwrite(dset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), where,
        "write dataset " + name);
}

void write_string_dataset(hid_t loc, const std::string &name, const std::string &value,
                          const std::string &where) {
  const Datatype type = string_type(where);
  const char *text = value.c_str();
  write_dataset(loc, name, type.get(), std::span<const hsize_t>(), &text, where);
}

// Rows per chunk: about 32 KiB of doubles per chunk, at most 256 rows, at least one (small
// enough for short runs, large enough that long runs do not drown in chunk metadata).
static hsize_t chunk_rows(const std::vector<hsize_t> &sample_shape) {
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
  write_rows(dset, row, 1, type, sample_shape, data, where, name);
}

void write_rows(const h5::Dataset &dset, hsize_t first, hsize_t n, hid_t type,
                const std::vector<hsize_t> &sample_shape, const void *data,
                const std::string &where, const std::string &name) {
  std::vector<hsize_t> dims{first + n}, start{first}, count{n};
  for (const hsize_t n : sample_shape) {
    dims.push_back(n);
    start.push_back(0);
    count.push_back(n);
  }
  h5::check(H5Dset_extent(dset.get(), dims.data()), where, "extend dataset " + name);
  if (n == 0)
    return;
  const h5::Dataspace file_space(H5Dget_space(dset.get()), where, "get dataspace of " + name);
  h5::check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                count.data(), nullptr),
            where, "select row of " + name);
  const h5::Dataspace mem_space = h5::simple_dataspace(count, {}, where);
  h5::check(H5Dwrite(dset.get(), type, mem_space.get(), file_space.get(), H5P_DEFAULT, data), where,
            "write dataset " + name);
}

Group write_h5md_header(hid_t file, const std::string &scene_text, const std::string &where) {
  const Group h5md = create_group(file, "h5md", where);
  const std::array<std::int32_t, 2> version{1, 1};
  write_attribute<std::int32_t>(h5md.get(), "version", version, where);
  const Group creator = create_group(h5md.get(), "creator", where);
  write_string_attribute(creator.get(), "name", "narrows", where);
  write_string_attribute(creator.get(), "version", NARROWS_VERSION, where);
  Group parameters = create_group(file, "parameters", where);
  write_string_dataset(parameters.get(), "scene", scene_text, where);
  return parameters;
}

} // namespace narrows::io::h5
