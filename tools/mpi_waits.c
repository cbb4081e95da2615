/* Where a run waits: the seconds each process spends in the MPI calls that can block (halo
 * exchanges' MPI_Waitall and MPI_Mprobe, collectives), per call site (the call chain, up to 6
 * callers deep). PMPI interposition, LD_PRELOAD; tools/mpi_waits.py names the callers. At
 * MPI_Finalize each rank writes MPI_WAITS_OUT.<rank>: one line per site, "seconds calls call"
 * then its callers as "module+0xoffset" (calls beyond 512 sites: one line without callers,
 * "beyond_the_site_table"). Seconds include the message time itself; at a
 * synchronising call most of it is waiting for a slower rank.
 * Build: mpicc -shared -fPIC -O2 -o mpi_waits.so tools/mpi_waits.c */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <execinfo.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { DEPTH = 6, SITES = 512 };
typedef struct {
  const char *call;
  int frames;
  void *caller[DEPTH];
  double seconds;
  unsigned long long calls;
} Site;
static Site sites[SITES];
static int used;
static Site beyond = {"beyond_the_site_table", 0, {0}, 0.0, 0}; /* (written only if used) */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Adds dt to the site of the current call chain (frame 0 is record, frame 1 the MPI wrapper). */
static void record(const char *call, double dt) {
  void *f[DEPTH + 2];
  int n = backtrace(f, DEPTH + 2) - 2;
  if (n < 0)
    n = 0;
  for (int i = 0; i < used; ++i)
    if (sites[i].call == call && sites[i].frames == n &&
        memcmp(sites[i].caller, f + 2, (size_t)n * sizeof(void *)) == 0) {
      sites[i].seconds += dt;
      sites[i].calls++;
      return;
    }
  if (used < SITES) {
    Site *s = &sites[used++];
    s->call = call;
    s->frames = n;
    memcpy(s->caller, f + 2, (size_t)n * sizeof(void *));
    s->seconds = dt;
    s->calls = 1;
  } else {
    beyond.seconds += dt;
    beyond.calls++;
  }
}

#define TIMED(call, expr)                                                                          \
  do {                                                                                             \
    const double t0 = now();                                                                       \
    const int result_ = (expr);                                                                    \
    record(call, now() - t0);                                                                      \
    return result_;                                                                                \
  } while (0)

int MPI_Waitall(int n, MPI_Request reqs[], MPI_Status st[]) {
  TIMED("waitall", PMPI_Waitall(n, reqs, st));
}
int MPI_Mprobe(int src, int tag, MPI_Comm comm, MPI_Message *m, MPI_Status *st) {
  TIMED("mprobe", PMPI_Mprobe(src, tag, comm, m, st));
}
int MPI_Sendrecv(const void *sb, int sc, MPI_Datatype st, int dest, int stag, void *rb, int rc,
                 MPI_Datatype rt, int src, int rtag, MPI_Comm comm, MPI_Status *status) {
  TIMED("sendrecv", PMPI_Sendrecv(sb, sc, st, dest, stag, rb, rc, rt, src, rtag, comm, status));
}
int MPI_Allreduce(const void *sb, void *rb, int c, MPI_Datatype t, MPI_Op op, MPI_Comm comm) {
  TIMED("allreduce", PMPI_Allreduce(sb, rb, c, t, op, comm));
}
int MPI_Allgather(const void *sb, int sc, MPI_Datatype st, void *rb, int rc, MPI_Datatype rt,
                  MPI_Comm comm) {
  TIMED("allgather", PMPI_Allgather(sb, sc, st, rb, rc, rt, comm));
}
int MPI_Barrier(MPI_Comm comm) { TIMED("barrier", PMPI_Barrier(comm)); }
int MPI_Neighbor_alltoall(const void *sb, int sc, MPI_Datatype st, void *rb, int rc,
                          MPI_Datatype rt, MPI_Comm comm) {
  TIMED("neighbor_alltoall", PMPI_Neighbor_alltoall(sb, sc, st, rb, rc, rt, comm));
}

int MPI_Finalize(void) {
  const char *out = getenv("MPI_WAITS_OUT");
  int me = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &me);
  if (out) {
    char name[4096];
    snprintf(name, sizeof name, "%s.%d", out, me);
    FILE *f = fopen(name, "w");
    if (f) {
      for (int i = 0; i < used; ++i) {
        fprintf(f, "%.6f %llu %s", sites[i].seconds, sites[i].calls, sites[i].call);
        for (int k = 0; k < sites[i].frames; ++k) {
          Dl_info d;
          if (dladdr(sites[i].caller[k], &d) && d.dli_fname)
            fprintf(f, " %s+0x%lx", d.dli_fname,
                    (unsigned long)((char *)sites[i].caller[k] - (char *)d.dli_fbase));
          else
            fprintf(f, " ?");
        }
        fprintf(f, "\n");
      }
      if (beyond.calls)
        fprintf(f, "%.6f %llu %s\n", beyond.seconds, beyond.calls, beyond.call);
      fclose(f);
    }
  }
  return PMPI_Finalize();
}
