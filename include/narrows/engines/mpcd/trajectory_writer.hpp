// Trajectory output of the mpcd engine: frames of the fluid (every particle, or those whose id
// is a multiple of a subsample stride) in an H5MD file, plus an XDMF description of the same
// file for ParaView.
//
// Layout of DIR/trajectory.h5 (H5MD 1.1 style):
//   /h5md                               attribute version = [1, 1]; group creator
//   /particles/fluid/box                attributes dimension, boundary; dataset edges [d]
//   /particles/fluid/position/{value [T][M][d], step [T], time [T]}
//   /particles/fluid/velocity/{value [T][M][d], step [T], time [T]}
//                                       (a series for each field of the species' table flagged
//                                       species::trajectory)
//   /particles/fluid/id                 [M]: row j holds the particle with id j * subsample
//   /particles/colloids/...             with colloids: every colloid, the same box, position and
//                                       velocity series, id [N_c] and radius [N_c], and
//                                       angular_velocity/{value [T][N_c][3], step, time},
//                                       orientation/{value [T][N_c][4] (w, x, y, z), step, time}
//   /parameters/{scene, subsample}
//   /contacts/...                       with spring contacts, the contact network of each frame
//                                       (Kanehl (thesis) fig 6.3), its rows concatenated frame
//                                       after frame (their number changes):
//     step [T], time [T]                the frames
//     first [T], count [T]              the frame's rows: first .. first + count - 1
//     ids [C][2]                        int64: the two colloid ids (owner < partner), or the
//                                       colloid and a wall: -1 the wall at y = 0, -2 at y = L_y
//     normal_force [C]                  |F_n| = k_n delta_n
//     sliding [C]                       int8: 1 if |F_t| is at the Coulomb cap mu |F_n|
// Rows are ordered by id, so a row is the same particle in every frame, on any rank count; the
// contacts of a frame are in key order (owner id, then partner id), also on any rank count.
// The XDMF has a temporal grid per species (colloids with their radius, for glyphs).
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_network.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/io/hdf5.hpp"

#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

namespace narrows::mpcd {

class TrajectoryWriter {
public:
  // Collective. Rank 0 creates `h5_path` (truncating) and writes the header; the XDMF file is
  // h5_path with .h5 replaced by .xdmf. The fluid has ids 0 .. total - 1. With `colloids`
  // (all of them on every rank: MpcdSimulation::gather_colloids), their frames go to
  // /particles/colloids; with `contacts` each frame also has a contact network (/contacts).
  TrajectoryWriter(const std::string &h5_path, const std::string &scene_text, const mpcd::Box &box,
                   std::uint64_t total, std::uint64_t subsample, MPI_Comm comm,
                   const colloids::Colloids *colloids = nullptr, bool contacts = false);

  // Collective: gathers the tracked particles on rank 0, which appends one frame (with the
  // colloids, if given to the constructor: pass the same species), flushes the file and
  // rewrites the XDMF. Throws narrows::Error if a tracked id is missing or repeated.
  // With contacts (constructor), `network` is the frame's (rank 0's is written).
  void write_frame(std::int64_t step, double time, const mpcd::Fluid &fluid,
                   const colloids::Colloids *colloids = nullptr,
                   const colloids::ContactNetwork *network = nullptr);

  std::uint64_t tracked() const { return rows_; }

private:
  // A series /particles/<species>/<field>/{step, time, value} of a trajectory field.
  struct Series {
    std::string prefix;         // "/particles/<species>/<field>/"
    int width = 1;              // values per row
    std::vector<hsize_t> shape; // of one frame: [M] or [M][width]
    io::h5::Dataset step, time, value;
  };

  void write_xdmf() const;
  void write_contacts(std::int64_t step, double time, const colloids::ContactNetwork &n);
  void write_colloid_frame(std::int64_t step, double time, const colloids::Colloids &c);
  // Appends a frame to each series: `rows` holds n rows of `width` values, the series' values
  // one after the other in the order of `series`.
  void write_series(std::vector<Series> &series, std::int64_t step, double time,
                    const std::vector<double> &rows, std::size_t n, std::size_t width);

  std::string path_, xdmf_path_;
  MPI_Comm comm_;
  int rank_ = 0, dim_ = 2;
  std::uint64_t subsample_ = 1, rows_ = 0;
  io::h5::File file_;
  std::size_t colloid_rows_ = 0; // 0: no colloid species
  std::vector<Series> fluid_series_, colloid_series_;
  std::vector<double> frame_times_;
  bool contacts_ = false;
  std::uint64_t contact_rows_ = 0; // rows of /contacts written so far
  io::h5::Dataset contact_step_, contact_time_, contact_first_, contact_count_, contact_ids_,
      contact_normal_, contact_sliding_;
  std::vector<std::uint64_t> send_rows_, recv_rows_;
  std::vector<double> send_values_, recv_values_, values_, buffer_;
};

} // namespace narrows::mpcd
