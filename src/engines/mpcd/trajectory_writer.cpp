// TrajectoryWriter: gathers the tracked fluid particles on rank 0 and appends H5MD frames.
#include "narrows/engines/mpcd/trajectory_writer.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>

namespace narrows::mpcd {

namespace h5 = io::h5;

namespace {

// The arrays of the trajectory fields of t, in table order (the writer checked they hold
// doubles).
std::vector<const std::vector<double> *> trajectory_columns(const species::Table &t) {
  std::vector<const std::vector<double> *> columns;
  for (const species::Field &f : t.fields())
    if (f.has(species::trajectory))
      for (const species::Column &c : f.columns())
        columns.push_back(std::get<std::vector<double> *>(c.array));
  return columns;
}

// A fixed-length string array attribute (H5MD's box/boundary).
void write_strings_attribute(hid_t obj, const std::string &name,
                             const std::vector<std::string> &values, const std::string &where) {
  std::size_t width = 1;
  for (const auto &v : values)
    width = std::max(width, v.size() + 1);
  std::vector<char> buf(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i].copy(&buf[i * width], values[i].size());
  const h5::Datatype type(H5Tcopy(H5T_C_S1), where, "copy string type");
  h5::check(H5Tset_size(type.get(), width), where, "set string size");
  const hsize_t n = values.size();
  h5::write_attribute(obj, name, type.get(), std::span<const hsize_t>(&n, 1), buf.data(), where);
}

std::string base_name(const std::string &path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

} // namespace

TrajectoryWriter::TrajectoryWriter(const std::string &h5_path, const std::string &scene_text,
                                   const mpcd::Box &box, std::uint64_t total,
                                   std::uint64_t subsample, MPI_Comm comm,
                                   const colloids::Colloids *colloids, bool contacts)
    : path_(h5_path), comm_(comm), dim_(box.dim), subsample_(subsample),
      rows_((total + subsample - 1) / subsample),
      colloid_rows_(colloids != nullptr ? colloids->size() : 0), contacts_(contacts) {
  MPI_Comm_rank(comm, &rank_);
  xdmf_path_ = path_.size() > 3 && path_.ends_with(".h5")
                   ? path_.substr(0, path_.size() - 3) + ".xdmf"
                   : path_ + ".xdmf";
  if (rank_ != 0)
    return;
  file_ = h5::create_file(path_);
  const h5::Group parameters = h5::write_h5md_header(file_.get(), scene_text, path_);
  h5::write_scalar<std::uint64_t>(parameters.get(), "subsample", subsample, path_);

  const h5::Group particles = h5::create_group(file_.get(), "particles", path_);
  // A species group with its box and id, and a series for each field of its table flagged
  // species::trajectory ([T][M][columns], or [T][M] for one column).
  auto species = [&](const species::Table &t, std::span<const std::uint64_t> ids,
                     std::vector<Series> &series) {
    h5::Group group = h5::create_group(particles.get(), std::string(t.species()), path_);
    const h5::Group box_group = h5::create_group(group.get(), "box", path_);
    const std::array<std::int32_t, 1> dimension{box.dim};
    h5::write_attribute<std::int32_t>(box_group.get(), "dimension", dimension, path_);
    std::vector<std::string> boundary;
    for (int k = 0; k < box.dim; ++k)
      boundary.push_back(k == 1 && box.walls_y ? "none" : "periodic");
    write_strings_attribute(box_group.get(), "boundary", boundary, path_);
    h5::write_dataset<double>(box_group.get(), "edges",
                              std::span<const double>(box.length.data(), box.dim), path_);
    h5::write_dataset<std::uint64_t>(group.get(), "id", ids, path_);
    for (const species::Field &f : t.fields()) {
      if (!f.has(species::trajectory))
        continue;
      for (const species::Column &c : f.columns())
        if (!std::holds_alternative<std::vector<double> *>(c.array))
          throw Error(ExitCode::other,
                      path_ + ": trajectory field " + std::string(f.name) + " is not of doubles");
      Series s;
      s.prefix = "/particles/" + std::string(t.species()) + "/" + std::string(f.name) + "/";
      s.width = f.count;
      s.shape = {ids.size()};
      if (f.shape != species::Shape::scalar)
        s.shape.push_back(static_cast<hsize_t>(f.count));
      const h5::Group g = h5::create_group(group.get(), std::string(f.name), path_);
      s.step = h5::create_series(g.get(), "step", H5T_STD_I64LE, {}, path_);
      s.time = h5::create_series(g.get(), "time", H5T_IEEE_F64LE, {}, path_);
      s.value = h5::create_series(g.get(), "value", H5T_IEEE_F64LE, s.shape, path_);
      series.push_back(std::move(s));
    }
    return group;
  };
  std::vector<std::uint64_t> ids(rows_);
  for (std::uint64_t j = 0; j < rows_; ++j)
    ids[j] = j * subsample;
  mpcd::Fluid fluid; // (its fields)
  fluid.dim = dim_;
  species(table(fluid), ids, fluid_series_);
  if (colloid_rows_ > 0) {
    const h5::Group group = species(table(*colloids), colloids->id, colloid_series_);
    // Once: the radius does not change (the XDMF sizes the glyphs by it).
    h5::write_dataset<double>(group.get(), "radius", colloids->radius, path_);
  }
  if (contacts_) {
    const h5::Group g = h5::create_group(file_.get(), "contacts", path_);
    contact_step_ = h5::create_series(g.get(), "step", H5T_STD_I64LE, {}, path_);
    contact_time_ = h5::create_series(g.get(), "time", H5T_IEEE_F64LE, {}, path_);
    contact_first_ = h5::create_series(g.get(), "first", H5T_STD_I64LE, {}, path_);
    contact_count_ = h5::create_series(g.get(), "count", H5T_STD_I64LE, {}, path_);
    contact_ids_ = h5::create_series(g.get(), "ids", H5T_STD_I64LE, {2}, path_);
    contact_normal_ = h5::create_series(g.get(), "normal_force", H5T_IEEE_F64LE, {}, path_);
    contact_sliding_ = h5::create_series(g.get(), "sliding", H5T_STD_I8LE, {}, path_);
  }
  h5::flush(file_, path_);
}

void TrajectoryWriter::write_contacts(std::int64_t step, double time,
                                      const colloids::ContactNetwork &n) {
  const hsize_t frame = frame_times_.size(), rows = n.size();
  std::vector<std::int64_t> ids(2 * rows);
  std::vector<std::int8_t> sliding(rows);
  for (std::size_t j = 0; j < rows; ++j) {
    ids[2 * j] = static_cast<std::int64_t>(n.owner[j]);
    const std::uint64_t p = n.partner[j];
    ids[2 * j + 1] = p == colloids::wall_low_id    ? -1
                     : p == colloids::wall_high_id ? -2
                                                   : static_cast<std::int64_t>(p);
    sliding[j] = static_cast<std::int8_t>(n.sliding[j]);
  }
  const auto first = static_cast<std::int64_t>(contact_rows_);
  const auto count = static_cast<std::int64_t>(rows);
  const std::string g = "/contacts/";
  h5::write_rows(contact_ids_, contact_rows_, rows, H5T_NATIVE_INT64, {2}, ids.data(), path_,
                 g + "ids");
  h5::write_rows(contact_normal_, contact_rows_, rows, H5T_NATIVE_DOUBLE, {}, n.normal.data(),
                 path_, g + "normal_force");
  h5::write_rows(contact_sliding_, contact_rows_, rows, H5T_NATIVE_INT8, {}, sliding.data(), path_,
                 g + "sliding");
  // The frame's rows last: a reader sees a frame only once its rows are there.
  h5::write_row(contact_first_, frame, H5T_NATIVE_INT64, {}, &first, path_, g + "first");
  h5::write_row(contact_count_, frame, H5T_NATIVE_INT64, {}, &count, path_, g + "count");
  h5::write_row(contact_time_, frame, H5T_NATIVE_DOUBLE, {}, &time, path_, g + "time");
  h5::write_row(contact_step_, frame, H5T_NATIVE_INT64, {}, &step, path_, g + "step");
  contact_rows_ += rows;
}

void TrajectoryWriter::write_series(std::vector<Series> &series, std::int64_t step, double time,
                                    const std::vector<double> &rows, std::size_t n,
                                    std::size_t width) {
  // rows: n rows of `width` values, the series' columns one after the other.
  const hsize_t frame = frame_times_.size();
  std::size_t first = 0;
  for (Series &s : series) {
    buffer_.resize(n * s.width);
    for (std::size_t a = 0; a < n; ++a)
      for (int k = 0; k < s.width; ++k)
        buffer_[a * s.width + k] = rows[a * width + first + k];
    first += s.width;
    h5::write_row(s.step, frame, H5T_NATIVE_INT64, {}, &step, path_, s.prefix + "step");
    h5::write_row(s.time, frame, H5T_NATIVE_DOUBLE, {}, &time, path_, s.prefix + "time");
    h5::write_row(s.value, frame, H5T_NATIVE_DOUBLE, s.shape, buffer_.data(), path_,
                  s.prefix + "value");
  }
}

void TrajectoryWriter::write_colloid_frame(std::int64_t step, double time,
                                           const colloids::Colloids &c) {
  if (c.size() != colloid_rows_)
    throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) + " has " +
                                     std::to_string(c.size()) + " colloids, expected " +
                                     std::to_string(colloid_rows_));
  // The rows of the trajectory fields (every colloid is here, in id order).
  const std::vector<const std::vector<double> *> columns = trajectory_columns(table(c));
  const std::size_t width = columns.size();
  values_.assign(colloid_rows_ * width, 0.0);
  for (std::size_t k = 0; k < width; ++k)
    for (std::size_t i = 0; i < colloid_rows_; ++i)
      values_[i * width + k] = (*columns[k])[i];
  write_series(colloid_series_, step, time, values_, colloid_rows_, width);
}

void TrajectoryWriter::write_frame(std::int64_t step, double time, const mpcd::Fluid &fluid,
                                   const colloids::Colloids *colloids,
                                   const colloids::ContactNetwork *network) {
  if ((colloids != nullptr) != (colloid_rows_ > 0))
    throw Error(ExitCode::other, path_ + ": write_frame " +
                                     (colloids ? "given colloids the file has no group for"
                                               : "without the colloids the file expects"));
  if ((network != nullptr) != contacts_)
    throw Error(ExitCode::other, path_ + ": write_frame " +
                                     (network ? "given contacts the file has no group for"
                                              : "without the contacts the file expects"));
  // This rank's tracked particles: row, then the values of the trajectory fields.
  const std::vector<const std::vector<double> *> columns = trajectory_columns(table(fluid));
  const std::size_t width = columns.size();
  send_rows_.clear();
  send_values_.clear();
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    if (fluid.id[i] % subsample_ != 0)
      continue;
    send_rows_.push_back(fluid.id[i] / subsample_);
    for (const auto *a : columns)
      send_values_.push_back((*a)[i]);
  }
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  const int mine = static_cast<int>(send_rows_.size());
  std::vector<int> counts(rank_ == 0 ? ranks : 0), offsets(counts.size());
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  int all = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = all;
    all += counts[r];
  }
  recv_rows_.resize(rank_ == 0 ? all : 0);
  MPI_Gatherv(send_rows_.data(), mine, MPI_UINT64_T, recv_rows_.data(), counts.data(),
              offsets.data(), MPI_UINT64_T, 0, comm_);
  const int w = static_cast<int>(width);
  for (std::size_t r = 0; r < counts.size(); ++r) {
    counts[r] *= w;
    offsets[r] *= w;
  }
  recv_values_.resize(rank_ == 0 ? static_cast<std::size_t>(all) * width : 0);
  MPI_Gatherv(send_values_.data(), mine * w, MPI_DOUBLE, recv_values_.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, comm_);
  if (rank_ != 0)
    return;

  if (static_cast<std::uint64_t>(all) != rows_)
    throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) + " has " +
                                     std::to_string(all) + " tracked particles, expected " +
                                     std::to_string(rows_));
  values_.assign(rows_ * width, 0.0);
  std::vector<char> seen(rows_, 0);
  for (std::size_t j = 0; j < recv_rows_.size(); ++j) {
    const std::uint64_t row = recv_rows_[j];
    if (row >= rows_ || seen[row]++)
      throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) +
                                       ": particle id " + std::to_string(row * subsample_) +
                                       " is missing or repeated");
    std::copy_n(&recv_values_[j * width], width, &values_[row * width]);
  }
  write_series(fluid_series_, step, time, values_, rows_, width);
  if (colloids != nullptr)
    write_colloid_frame(step, time, *colloids);
  if (network != nullptr)
    write_contacts(step, time, *network);
  h5::flush(file_, path_);
  frame_times_.push_back(time);
  write_xdmf();
}

void TrajectoryWriter::write_xdmf() const {
  // Written to a temporary name and renamed, so a reader never sees half a file.
  const std::string tmp = xdmf_path_ + ".tmp";
  {
    std::ofstream out(tmp);
    const std::string h5 = base_name(path_);
    const std::string d = std::to_string(dim_);
    const std::string t = std::to_string(frame_times_.size());
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n";
    // One temporal collection per species; the colloids also carry their radius.
    auto collection = [&](const std::string &name, std::size_t rows) {
      const std::string m = std::to_string(rows);
      out << "<Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
      for (std::size_t f = 0; f < frame_times_.size(); ++f) {
        auto slab = [&](const char *field) {
          return "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" + m + " " + d +
                 "\">\n <DataItem Dimensions=\"3 3\" Format=\"XML\">" + std::to_string(f) +
                 " 0 0 1 1 1 1 " + m + " " + d + "</DataItem>\n <DataItem Dimensions=\"" + t + " " +
                 m + " " + d + "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5 +
                 ":/particles/" + name + "/" + field + "/value</DataItem>\n</DataItem>\n";
        };
        char time[40];
        std::snprintf(time, sizeof time, "%.17g", frame_times_[f]);
        out << "<Grid Name=\"frame " << f << "\" GridType=\"Uniform\">\n<Time Value=\"" << time
            << "\"/>\n<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << m << "\"/>\n"
            << "<Geometry GeometryType=\"" << (dim_ == 3 ? "XYZ" : "XY") << "\">\n"
            << slab("position") << "</Geometry>\n"
            << "<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n"
            << slab("velocity") << "</Attribute>\n";
        if (name == "colloids")
          out << "<Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">\n"
              << "<DataItem Dimensions=\"" << m
              << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5
              << ":/particles/colloids/radius</DataItem>\n</Attribute>\n";
        out << "</Grid>\n";
      }
      out << "</Grid>\n";
    };
    collection("fluid", rows_);
    if (colloid_rows_ > 0)
      collection("colloids", colloid_rows_);
    out << "</Domain>\n</Xdmf>\n";
    if (!out)
      throw Error(ExitCode::other, tmp + ": cannot write the XDMF description");
  }
  if (std::rename(tmp.c_str(), xdmf_path_.c_str()) != 0)
    throw Error(ExitCode::other, xdmf_path_ + ": cannot rename " + tmp);
}

} // namespace narrows::mpcd
