// One error for all ranks: MPI_Allreduce of who failed, then the first failure's message is
// broadcast and thrown everywhere.
#include "narrows/run/collective.hpp"

#include "narrows/core/error.hpp"

#include <unistd.h>

#include <new>
#include <string>

namespace narrows::run {

void collectively(MPI_Comm comm, const std::function<void()> &work) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int code = 0, failed = 0;
  std::string message;
  try {
    work();
  } catch (const Error &e) {
    failed = 1; // also for ExitCode::ok: "nothing to run" ends the run without output
    code = static_cast<int>(e.code());
    message = e.what();
  } catch (const std::bad_alloc &) {
    failed = 1;
    code = static_cast<int>(ExitCode::other);
    message = "internal error: out of memory (std::bad_alloc)";
  } catch (const std::exception &e) {
    failed = 1;
    code = static_cast<int>(ExitCode::other);
    message = std::string("internal error: ") + e.what();
  }
  const int mine = failed ? rank : ranks;
  int first = ranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == ranks)
    return;
  unsigned long length = message.size();
  MPI_Bcast(&code, 1, MPI_INT, first, comm);
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG, first, comm);
  message.resize(length);
  MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, first, comm);
  throw Error(static_cast<ExitCode>(code), message);
}

double memory_per_rank(MPI_Comm comm) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int on_node = 1;
  MPI_Comm_size(node, &on_node);
  MPI_Comm_free(&node);
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(sysconf(_SC_PAGESIZE));
  return pages * page / on_node;
}

} // namespace narrows::run
