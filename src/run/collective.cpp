// One error for all ranks: MPI_Allreduce of who failed, then the first failure's message is
// broadcast and thrown everywhere.
#include "narrows/run/collective.hpp"

#include "narrows/core/error.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
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

namespace {

MPI_Win abort_window = MPI_WIN_NULL;
int *abort_count = nullptr; // on rank 0 of MPI_COMM_WORLD: the failing ranks so far

} // namespace

void open_abort_line() {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks < 2 || abort_window != MPI_WIN_NULL)
    return;
  // An MPI without one-sided communication must not end every run here: without the window
  // each failing rank prints its line, as before.
  MPI_Errhandler was;
  MPI_Comm_get_errhandler(MPI_COMM_WORLD, &was);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  const int rc = MPI_Win_allocate(rank == 0 ? static_cast<MPI_Aint>(sizeof(int)) : 0, sizeof(int),
                                  MPI_INFO_NULL, MPI_COMM_WORLD, &abort_count, &abort_window);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, was);
  MPI_Errhandler_free(&was);
  int ok = rc == MPI_SUCCESS ? 1 : 0, all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (!all) { // (a window some ranks hold is left to MPI_Finalize)
    abort_window = MPI_WIN_NULL;
    abort_count = nullptr;
    return;
  }
  if (rank == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, abort_window);
    *abort_count = 0;
    MPI_Win_unlock(0, abort_window);
  }
  MPI_Barrier(MPI_COMM_WORLD); // the counter is 0 before any rank may claim it
}

void close_abort_line() {
  if (abort_window != MPI_WIN_NULL)
    MPI_Win_free(&abort_window);
  abort_count = nullptr;
}

void abort_with_line(MPI_Comm comm, const std::string &line, int code, double grace_seconds) {
  int before = 0;
  if (abort_window != MPI_WIN_NULL) {
    const int one = 1;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, abort_window);
    MPI_Fetch_and_op(&one, &before, MPI_INT, 0, 0, MPI_SUM, abort_window);
    MPI_Win_unlock(0, abort_window);
  }
  if (before == 0) {
    std::fprintf(stderr, "narrows: %s\n", line.c_str());
    std::fflush(stderr);
  } else { // another rank prints and aborts: wait for it to end this one too
    const double until = MPI_Wtime() + grace_seconds;
    while (MPI_Wtime() < until)
      usleep(10000);
  }
  MPI_Abort(comm, code);
  std::abort(); // (MPI_Abort does not return)
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
