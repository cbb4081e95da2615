// ObservablesWriter: layout, shapes and values read back with the HDF5 C API; shape changes throw.
#include "narrows/io/observables_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using narrows::io::ObservablesWriter;
namespace h5 = narrows::io::h5;

// A unique temporary file, removed at the end of the test.
class TempFile {
public:
  explicit TempFile(const std::string &stem) {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            (stem + "-" + info->name() + "-" + std::to_string(::getpid()) + ".h5");
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  std::string str() const { return path_.string(); }

private:
  std::filesystem::path path_;
};

std::vector<hsize_t> shape_of(hid_t file, const std::string &name) {
  const h5::Dataset dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), name, "open dataset");
  const h5::Dataspace space(H5Dget_space(dset.get()), name, "get dataspace");
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space.get()));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

template <class T> std::vector<T> read_all(hid_t file, const std::string &name) {
  const h5::Dataset dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), name, "open dataset");
  const h5::Dataspace space(H5Dget_space(dset.get()), name, "get dataspace");
  std::vector<T> data(H5Sget_simple_extent_npoints(space.get()));
  h5::check(H5Dread(dset.get(), h5::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
            name, "read");
  return data;
}

std::string read_string_dataset(hid_t file, const std::string &name) {
  const h5::Dataset dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), name, "open dataset");
  const h5::Datatype type = h5::string_type(name);
  char *text = nullptr;
  h5::check(H5Dread(dset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text), name, "read");
  std::string result(text);
  H5free_memory(text);
  return result;
}

std::string read_string_attribute(hid_t file, const std::string &object, const std::string &name) {
  const h5::Attribute attr(
      H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), name,
      "open attribute");
  const h5::Datatype type = h5::string_type(name);
  char *text = nullptr;
  h5::check(H5Aread(attr.get(), type.get(), &text), name, "read attribute");
  std::string result(text);
  H5free_memory(text);
  return result;
}

TEST(ObservablesWriter, WritesLayoutAndSamples) {
  TempFile tmp("narrows-observables");
  const std::string scene = "[run]\nengine = \"mpcd\"\nsteps = 20\n";
  {
    ObservablesWriter w(tmp.str(), scene);
    for (int i = 0; i < 3; ++i) {
      const std::int64_t step = 10 * i;
      const double time = 0.1 * step;
      w.append_scalar("temperature", step, time, 1.0 + 0.5 * i);
      const std::vector<double> momentum{1.0 * i, -2.0 * i, 0.25};
      w.append_vector("momentum", step, time, momentum);
      const std::vector<double> bins{0.5, 1.5, 2.5, 3.5};
      std::vector<double> velocity(bins.size() * 2);
      for (std::size_t b = 0; b < velocity.size(); ++b)
        velocity[b] = 100.0 * i + static_cast<double>(b);
      w.append_profile("velocity_profile", step, time, bins, velocity, 2);
      const std::vector<double> density{10.0 + i, 11.0, 12.0, 13.0 - i};
      w.append_profile("density_profile", step, time, bins, density, 1);
      w.flush();
    }
  }

  const h5::File file = h5::open_file(tmp.str());
  const hid_t f = file.get();

  // Header: /h5md version and creator, the scene text.
  {
    const h5::Attribute attr(H5Aopen_by_name(f, "h5md", "version", H5P_DEFAULT, H5P_DEFAULT),
                             "h5md", "open attribute");
    std::array<int, 2> version{};
    ASSERT_GE(H5Aread(attr.get(), H5T_NATIVE_INT, version.data()), 0);
    EXPECT_EQ(version[0], 1);
    EXPECT_EQ(version[1], 1);
  }
  EXPECT_EQ(read_string_attribute(f, "h5md/creator", "name"), "narrows");
  EXPECT_FALSE(read_string_attribute(f, "h5md/creator", "version").empty());
  EXPECT_EQ(read_string_dataset(f, "parameters/scene"), scene);

  // Time axis, identical for every series.
  for (const std::string name :
       {"temperature", "momentum", "velocity_profile", "density_profile"}) {
    const std::string group = "observables/" + name;
    EXPECT_EQ(shape_of(f, group + "/step"), (std::vector<hsize_t>{3})) << name;
    EXPECT_EQ(shape_of(f, group + "/time"), (std::vector<hsize_t>{3})) << name;
    EXPECT_EQ(read_all<std::int64_t>(f, group + "/step"), (std::vector<std::int64_t>{0, 10, 20}))
        << name;
    EXPECT_EQ(read_all<double>(f, group + "/time"), (std::vector<double>{0.0, 1.0, 2.0})) << name;
  }

  EXPECT_EQ(shape_of(f, "observables/temperature/value"), (std::vector<hsize_t>{3}));
  EXPECT_EQ(read_all<double>(f, "observables/temperature/value"),
            (std::vector<double>{1.0, 1.5, 2.0}));

  EXPECT_EQ(shape_of(f, "observables/momentum/value"), (std::vector<hsize_t>{3, 3}));
  EXPECT_EQ(read_all<double>(f, "observables/momentum/value"),
            (std::vector<double>{0.0, 0.0, 0.25, 1.0, -2.0, 0.25, 2.0, -4.0, 0.25}));

  EXPECT_EQ(shape_of(f, "observables/velocity_profile/value"), (std::vector<hsize_t>{3, 4, 2}));
  EXPECT_EQ(shape_of(f, "observables/velocity_profile/bins"), (std::vector<hsize_t>{4}));
  EXPECT_EQ(read_all<double>(f, "observables/velocity_profile/bins"),
            (std::vector<double>{0.5, 1.5, 2.5, 3.5}));
  const auto velocity = read_all<double>(f, "observables/velocity_profile/value");
  ASSERT_EQ(velocity.size(), 24u);
  for (std::size_t t = 0; t < 3; ++t)
    for (std::size_t k = 0; k < 8; ++k)
      EXPECT_EQ(velocity[8 * t + k], 100.0 * t + k);

  EXPECT_EQ(shape_of(f, "observables/density_profile/value"), (std::vector<hsize_t>{3, 4}));
  EXPECT_EQ(read_all<double>(f, "observables/density_profile/value"),
            (std::vector<double>{10, 11, 12, 13, 11, 11, 12, 12, 12, 11, 12, 11}));
}

TEST(ObservablesWriter, ShapeChangeThrows) {
  TempFile tmp("narrows-observables");
  ObservablesWriter w(tmp.str(), "");
  const std::vector<double> three{1, 2, 3}, two{1, 2};
  const std::vector<double> bins{0.5, 1.5};
  w.append_vector("momentum", 0, 0.0, three);
  EXPECT_THROW(w.append_vector("momentum", 1, 0.1, two), narrows::Error);
  EXPECT_THROW(w.append_scalar("momentum", 1, 0.1, 1.0), narrows::Error);
  w.append_scalar("temperature", 0, 0.0, 1.0);
  EXPECT_THROW(w.append_vector("temperature", 1, 0.1, three), narrows::Error);
  // Same element count but a profile, not a vector: still a different observable kind.
  EXPECT_THROW(w.append_profile("momentum", 1, 0.1, std::vector<double>{0.5, 1.5, 2.5}, three, 1),
               narrows::Error);
  w.append_profile("velocity_profile", 0, 0.0, bins, std::vector<double>{1, 2, 3, 4}, 2);
  EXPECT_THROW(
      w.append_profile("velocity_profile", 1, 0.1, bins, std::vector<double>{1, 2, 3, 4, 5, 6}, 3),
      narrows::Error);
  EXPECT_THROW(w.append_profile("velocity_profile", 1, 0.1, std::vector<double>{0.5, 1.5, 2.5},
                                std::vector<double>{1, 2, 3, 4, 5, 6}, 2),
               narrows::Error);
  // Inconsistent sizes within one call.
  EXPECT_THROW(w.append_profile("other", 0, 0.0, bins, three, 2), narrows::Error);
  // A good append after the failures still works and the error names the file.
  w.append_vector("momentum", 1, 0.1, three);
  try {
    w.append_vector("momentum", 2, 0.2, two);
    FAIL() << "no throw";
  } catch (const narrows::Error &e) {
    EXPECT_EQ(e.code(), narrows::ExitCode::other);
    EXPECT_NE(std::string(e.what()).find(tmp.str()), std::string::npos);
  }
  w.flush();
  const h5::File file = h5::open_file(tmp.str());
  EXPECT_EQ(shape_of(file.get(), "observables/momentum/value"), (std::vector<hsize_t>{2, 3}));
}

TEST(ObservablesWriter, ProfilesShareBinsAndSteps) {
  // A set of profiles (axial_fields): one dataset [T][bins] per field beside step, time, bins,
  // and no value; a sample with other fields, or other bins, throws.
  TempFile tmp("narrows-observables");
  {
    ObservablesWriter w(tmp.str(), "");
    const std::vector<double> bins{1, 3, 5}, a{0.1, 0.2, 0.3}, b{-1, -2, -3};
    w.append_profiles("axial_fields", 10, 1.0, bins, {{"phi", a}, {"velocity", b}});
    w.append_profiles("axial_fields", 20, 2.0, bins, {{"phi", b}, {"velocity", a}});
    EXPECT_THROW(w.append_profiles("axial_fields", 30, 3.0, bins, {{"phi", a}}), narrows::Error);
    EXPECT_THROW(w.append_profiles("axial_fields", 30, 3.0, bins, {{"phi", a}, {"v", b}}),
                 narrows::Error);
    EXPECT_THROW(w.append_profiles("axial_fields", 30, 3.0, std::vector<double>{1, 3},
                                   {{"phi", a}, {"velocity", b}}),
                 narrows::Error);
    EXPECT_THROW(w.append_profiles("other", 0, 0.0, bins, {{"step", a}}), narrows::Error);
  }
  const h5::File file = h5::open_file(tmp.str());
  EXPECT_EQ(shape_of(file.get(), "observables/axial_fields/phi"), (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(read_all<double>(file.get(), "observables/axial_fields/velocity"),
            (std::vector<double>{-1, -2, -3, 0.1, 0.2, 0.3}));
  EXPECT_EQ(read_all<std::int64_t>(file.get(), "observables/axial_fields/step"),
            (std::vector<std::int64_t>{10, 20}));
  EXPECT_EQ(read_all<double>(file.get(), "observables/axial_fields/bins"),
            (std::vector<double>{1, 3, 5}));
  EXPECT_LT(H5Lexists(file.get(), "observables/axial_fields/value", H5P_DEFAULT), 1);
}

TEST(ObservablesWriter, UnwritablePathThrows) {
  try {
    ObservablesWriter w("/nonexistent-dir-narrows/observables.h5", "");
    FAIL() << "no throw";
  } catch (const narrows::Error &e) {
    EXPECT_EQ(e.code(), narrows::ExitCode::other);
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent-dir-narrows/observables.h5: HDF5 create file failed");
  }
}

} // namespace

// A field with datasets of one row per sample beside value (contact_statistics): each grows with
// value, carries per_sample = 1, the axes are written once; a changed key set or shape throws.
TEST(ObservablesWriter, FieldWithDatasetsBeside) {
  TempFile tmp("narrows-observables");
  {
    ObservablesWriter w(tmp.str(), "");
    using B = ObservablesWriter::Beside;
    const std::vector<double> value{1, 2, 3, 4, 5, 6}, two{7, 8}, one{9};
    for (int s = 0; s < 3; ++s)
      w.append_field("stats", s * 10, s * 1.0, {2, 3}, value,
                     {B{"pair", {2}, two}, B{"scalar", {}, one}}, {{"bins", {0.5, 1.5, 2.5}}});
    EXPECT_THROW(w.append_field("stats", 30, 3.0, {2, 3}, value, {B{"pair", {2}, two}}, {}),
                 narrows::Error);
    EXPECT_THROW(w.append_field("stats", 30, 3.0, {2, 3}, value,
                                {B{"pair", {1}, one}, B{"scalar", {}, one}}, {}),
                 narrows::Error);
    EXPECT_THROW(w.append_field("other", 0, 0.0, {2}, two, {B{"value", {1}, one}}, {}),
                 narrows::Error);
    EXPECT_THROW(w.append_field("other", 0, 0.0, {2}, two, {B{"x", {2}, one}}, {}), narrows::Error);
    w.flush();
  }
  const h5::File file = h5::open_file(tmp.str());
  EXPECT_EQ(shape_of(file.get(), "observables/stats/value"), (std::vector<hsize_t>{3, 2, 3}));
  EXPECT_EQ(shape_of(file.get(), "observables/stats/pair"), (std::vector<hsize_t>{3, 2}));
  EXPECT_EQ(shape_of(file.get(), "observables/stats/scalar"), (std::vector<hsize_t>{3}));
  EXPECT_EQ(read_all<double>(file.get(), "observables/stats/pair"),
            (std::vector<double>{7, 8, 7, 8, 7, 8}));
  EXPECT_EQ(read_all<double>(file.get(), "observables/stats/bins"),
            (std::vector<double>{0.5, 1.5, 2.5}));
  EXPECT_EQ(read_all<std::int64_t>(file.get(), "observables/stats/step"),
            (std::vector<std::int64_t>{0, 10, 20}));
  EXPECT_GT(H5Aexists_by_name(file.get(), "observables/stats/pair", "per_sample", H5P_DEFAULT), 0);
  EXPECT_GT(H5Aexists_by_name(file.get(), "observables/stats/scalar", "per_sample", H5P_DEFAULT),
            0);
}
