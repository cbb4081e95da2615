// One-column halo exchange of x-slabs (see lattice/column_halo.hpp).
#include "narrows/engines/lgca/column_halo.hpp"

#include <mpi.h>

#include <cstring>
#include <vector>

namespace narrows::lgca {

void exchange_column_halos(const parallel::Slabs &slabs, void *base, std::size_t stride, int rows,
                           int nx, std::size_t elem_bytes, int tag) {
  auto *bytes = static_cast<unsigned char *>(base);
  const auto at = [&](int y, int col) {
    return bytes +
           (static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(col)) * elem_bytes;
  };
  if (slabs.ranks() == 1) {
    for (int y = 0; y < rows; ++y) {
      std::memcpy(at(y, 0), at(y, nx), elem_bytes);
      std::memcpy(at(y, nx + 1), at(y, 1), elem_bytes);
    }
    return;
  }
  const int left = (slabs.rank() + slabs.ranks() - 1) % slabs.ranks();
  const int right = (slabs.rank() + 1) % slabs.ranks();
  const std::size_t n = static_cast<std::size_t>(rows) * elem_bytes;
  std::vector<unsigned char> send(n), recv(n);
  // My first column goes to the left neighbour's right halo, my last to the right one's left.
  for (int pass = 0; pass < 2; ++pass) {
    const int src_col = pass == 0 ? 1 : nx;
    const int dst_col = pass == 0 ? nx + 1 : 0;
    const int to = pass == 0 ? left : right, from = pass == 0 ? right : left;
    for (int y = 0; y < rows; ++y)
      std::memcpy(send.data() + static_cast<std::size_t>(y) * elem_bytes, at(y, src_col),
                  elem_bytes);
    MPI_Sendrecv(send.data(), static_cast<int>(n), MPI_BYTE, to, tag + pass, recv.data(),
                 static_cast<int>(n), MPI_BYTE, from, tag + pass, slabs.comm(), MPI_STATUS_IGNORE);
    for (int y = 0; y < rows; ++y)
      std::memcpy(at(y, dst_col), recv.data() + static_cast<std::size_t>(y) * elem_bytes,
                  elem_bytes);
  }
}

} // namespace narrows::lgca
