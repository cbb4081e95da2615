// The RAII HDF5 layer: checked file/group/dataspace creation and small-write helpers.
#include "narrows/io/hdf5.hpp"

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

} // namespace narrows::io::h5
