// TrajectoryWriter: gathers the tracked fluid particles on rank 0 and appends H5MD frames.
#include "narrows/engines/mpcd/trajectory_writer.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <tuple>

namespace narrows::mpcd {

namespace h5 = io::h5;

namespace {

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
                                   const colloids::Colloids *colloids)
    : path_(h5_path), comm_(comm), dim_(box.dim), subsample_(subsample),
      rows_((total + subsample - 1) / subsample),
      colloid_rows_(colloids != nullptr ? colloids->size() : 0) {
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
  // A species group with its box and id; its position and velocity series go to the arrays.
  auto species = [&](const char *name, std::span<const std::uint64_t> ids, h5::Dataset *step,
                     h5::Dataset *time, h5::Dataset *value) {
    h5::Group group = h5::create_group(particles.get(), name, path_);
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
    const std::vector<hsize_t> shape{ids.size(), static_cast<hsize_t>(dim_)};
    const char *names[2] = {"position", "velocity"};
    for (int f = 0; f < 2; ++f) {
      const h5::Group g = h5::create_group(group.get(), names[f], path_);
      step[f] = h5::create_series(g.get(), "step", H5T_STD_I64LE, {}, path_);
      time[f] = h5::create_series(g.get(), "time", H5T_IEEE_F64LE, {}, path_);
      value[f] = h5::create_series(g.get(), "value", H5T_IEEE_F64LE, shape, path_);
    }
    return group;
  };
  std::vector<std::uint64_t> ids(rows_);
  for (std::uint64_t j = 0; j < rows_; ++j)
    ids[j] = j * subsample;
  species("fluid", ids, step_, time_, value_);
  if (colloid_rows_ > 0) {
    const h5::Group group =
        species("colloids", colloids->id, colloid_step_, colloid_time_, colloid_value_);
    h5::write_dataset<double>(group.get(), "radius", colloids->radius, path_);
    for (auto [series, name, m] : {std::tuple{&spin_, "angular_velocity", hsize_t{3}},
                                   std::tuple{&turn_, "orientation", hsize_t{4}}}) {
      const h5::Group g = h5::create_group(group.get(), name, path_);
      series->name = name;
      series->step = h5::create_series(g.get(), "step", H5T_STD_I64LE, {}, path_);
      series->time = h5::create_series(g.get(), "time", H5T_IEEE_F64LE, {}, path_);
      series->value =
          h5::create_series(g.get(), "value", H5T_IEEE_F64LE, {colloid_rows_, m}, path_);
    }
  }
  h5::flush(file_, path_);
}

void TrajectoryWriter::write_colloid_frame(std::int64_t step, double time,
                                           const colloids::Colloids &c) {
  if (c.size() != colloid_rows_)
    throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) + " has " +
                                     std::to_string(c.size()) + " colloids, expected " +
                                     std::to_string(colloid_rows_));
  // The fluid's row buffers are free again (its frame is written): reuse them.
  position_.assign(colloid_rows_ * dim_, 0.0);
  velocity_.assign(colloid_rows_ * dim_, 0.0);
  for (std::size_t a = 0; a < colloid_rows_; ++a)
    for (int k = 0; k < dim_; ++k) {
      position_[a * dim_ + k] = c.x[k][a];
      velocity_[a * dim_ + k] = c.v[k][a];
    }
  const double *data[2] = {position_.data(), velocity_.data()};
  const std::vector<hsize_t> shape{colloid_rows_, static_cast<hsize_t>(dim_)};
  const hsize_t frame = frame_times_.size();
  const char *names[2] = {"position", "velocity"};
  for (int f = 0; f < 2; ++f) {
    const std::string prefix = std::string("/particles/colloids/") + names[f] + "/";
    h5::write_row(colloid_step_[f], frame, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
    h5::write_row(colloid_time_[f], frame, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
    h5::write_row(colloid_value_[f], frame, H5T_NATIVE_DOUBLE, shape, data[f], path_,
                  prefix + "value");
  }
  // Angular velocity (all three components) and orientation (w, x, y, z): a series each.
  const auto rows = [&](ColloidSeries &series, const auto &components) {
    const std::size_t m = components.size();
    position_.assign(colloid_rows_ * m, 0.0);
    for (std::size_t a = 0; a < colloid_rows_; ++a)
      for (std::size_t k = 0; k < m; ++k)
        position_[a * m + k] = components[k][a];
    const std::string prefix = "/particles/colloids/" + series.name + "/";
    h5::write_row(series.step, frame, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
    h5::write_row(series.time, frame, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
    h5::write_row(series.value, frame, H5T_NATIVE_DOUBLE, {colloid_rows_, m}, position_.data(),
                  path_, prefix + "value");
  };
  rows(spin_, c.omega);
  rows(turn_, c.q);
}

void TrajectoryWriter::write_frame(std::int64_t step, double time, const mpcd::Fluid &fluid,
                                   const colloids::Colloids *colloids) {
  if ((colloids != nullptr) != (colloid_rows_ > 0))
    throw Error(ExitCode::other, path_ + ": write_frame " +
                                     (colloids ? "given colloids the file has no group for"
                                               : "without the colloids the file expects"));
  // This rank's tracked particles: row, then position and velocity.
  send_rows_.clear();
  send_values_.clear();
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    if (fluid.id[i] % subsample_ != 0)
      continue;
    send_rows_.push_back(fluid.id[i] / subsample_);
    for (int k = 0; k < dim_; ++k)
      send_values_.push_back(fluid.x[k][i]);
    for (int k = 0; k < dim_; ++k)
      send_values_.push_back(fluid.v[k][i]);
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
  const int width = 2 * dim_;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    counts[r] *= width;
    offsets[r] *= width;
  }
  recv_values_.resize(rank_ == 0 ? static_cast<std::size_t>(all) * width : 0);
  MPI_Gatherv(send_values_.data(), mine * width, MPI_DOUBLE, recv_values_.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, comm_);
  if (rank_ != 0)
    return;

  if (static_cast<std::uint64_t>(all) != rows_)
    throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) + " has " +
                                     std::to_string(all) + " tracked particles, expected " +
                                     std::to_string(rows_));
  position_.assign(rows_ * dim_, 0.0);
  velocity_.assign(rows_ * dim_, 0.0);
  std::vector<char> seen(rows_, 0);
  for (std::size_t j = 0; j < recv_rows_.size(); ++j) {
    const std::uint64_t row = recv_rows_[j];
    if (row >= rows_ || seen[row]++)
      throw Error(ExitCode::other, path_ + ": frame at step " + std::to_string(step) +
                                       ": particle id " + std::to_string(row * subsample_) +
                                       " is missing or repeated");
    for (int k = 0; k < dim_; ++k) {
      position_[row * dim_ + k] = recv_values_[j * width + k];
      velocity_[row * dim_ + k] = recv_values_[j * width + dim_ + k];
    }
  }
  const std::vector<hsize_t> shape{rows_, static_cast<hsize_t>(dim_)};
  const hsize_t frame = frame_times_.size();
  const double *data[2] = {position_.data(), velocity_.data()};
  const char *names[2] = {"position", "velocity"};
  for (int f = 0; f < 2; ++f) {
    const std::string prefix = std::string("/particles/fluid/") + names[f] + "/";
    h5::write_row(step_[f], frame, H5T_NATIVE_INT64, {}, &step, path_, prefix + "step");
    h5::write_row(time_[f], frame, H5T_NATIVE_DOUBLE, {}, &time, path_, prefix + "time");
    h5::write_row(value_[f], frame, H5T_NATIVE_DOUBLE, shape, data[f], path_, prefix + "value");
  }
  if (colloids != nullptr)
    write_colloid_frame(step, time, *colloids);
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
