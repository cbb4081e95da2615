/* Counts the MPI collective and point-to-point calls of a process and the bytes they send
 * (PMPI interposition, LD_PRELOAD; tools/scaling_model.py). At MPI_Finalize each rank appends one
 * line to the file named by MPI_CALLS_OUT: rank, then "name calls bytes" for each call type.
 * Build: mpicc -shared -fPIC -O2 -o mpi_calls.so tools/mpi_calls.c */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

enum { ALLTOALL, ALLTOALLV, ALLREDUCE, REDUCE, BCAST, ALLGATHER, ALLGATHERV, GATHER, GATHERV,
       SCAN, EXSCAN, BARRIER, SENDRECV, SEND, ISEND, IRECV, MPROBE, IMRECV, WAITALL,
       NEIGHBOR_ALLTOALL, NEIGHBOR_ALLTOALLV, KINDS };
static const char *names[KINDS] = {"alltoall", "alltoallv", "allreduce", "reduce", "bcast",
                                   "allgather", "allgatherv", "gather", "gatherv", "scan",
                                   "exscan", "barrier", "sendrecv", "send", "isend", "irecv",
                                   "mprobe", "imrecv", "waitall", "neighbor_alltoall",
                                   "neighbor_alltoallv"};
static unsigned long long calls[KINDS], bytes[KINDS];

static long long size_of(MPI_Datatype t) {
  int s = 0;
  PMPI_Type_size(t, &s);
  return s;
}
#define COUNT(kind, n) (calls[kind]++, bytes[kind] += (unsigned long long)(n))

int MPI_Alltoall(const void *sb, int sc, MPI_Datatype st, void *rb, int rc, MPI_Datatype rt,
                 MPI_Comm comm) {
  int p = 0;
  PMPI_Comm_size(comm, &p);
  COUNT(ALLTOALL, (long long)sc * size_of(st) * (p - 1));
  return PMPI_Alltoall(sb, sc, st, rb, rc, rt, comm);
}
int MPI_Alltoallv(const void *sb, const int *sc, const int *sd, MPI_Datatype st, void *rb,
                  const int *rc, const int *rd, MPI_Datatype rt, MPI_Comm comm) {
  int p = 0, me = 0;
  PMPI_Comm_size(comm, &p);
  PMPI_Comm_rank(comm, &me);
  long long n = 0;
  for (int r = 0; r < p; ++r)
    if (r != me)
      n += sc[r];
  COUNT(ALLTOALLV, n * size_of(st));
  return PMPI_Alltoallv(sb, sc, sd, st, rb, rc, rd, rt, comm);
}
int MPI_Allreduce(const void *sb, void *rb, int c, MPI_Datatype t, MPI_Op op, MPI_Comm comm) {
  COUNT(ALLREDUCE, (long long)c * size_of(t));
  return PMPI_Allreduce(sb, rb, c, t, op, comm);
}
int MPI_Reduce(const void *sb, void *rb, int c, MPI_Datatype t, MPI_Op op, int root,
               MPI_Comm comm) {
  COUNT(REDUCE, (long long)c * size_of(t));
  return PMPI_Reduce(sb, rb, c, t, op, root, comm);
}
int MPI_Bcast(void *b, int c, MPI_Datatype t, int root, MPI_Comm comm) {
  COUNT(BCAST, (long long)c * size_of(t));
  return PMPI_Bcast(b, c, t, root, comm);
}
int MPI_Allgather(const void *sb, int sc, MPI_Datatype st, void *rb, int rc, MPI_Datatype rt,
                  MPI_Comm comm) {
  COUNT(ALLGATHER, (long long)sc * size_of(st));
  return PMPI_Allgather(sb, sc, st, rb, rc, rt, comm);
}
int MPI_Allgatherv(const void *sb, int sc, MPI_Datatype st, void *rb, const int *rc,
                   const int *rd, MPI_Datatype rt, MPI_Comm comm) {
  COUNT(ALLGATHERV, (long long)sc * size_of(st));
  return PMPI_Allgatherv(sb, sc, st, rb, rc, rd, rt, comm);
}
int MPI_Gather(const void *sb, int sc, MPI_Datatype st, void *rb, int rc, MPI_Datatype rt,
               int root, MPI_Comm comm) {
  COUNT(GATHER, (long long)sc * size_of(st));
  return PMPI_Gather(sb, sc, st, rb, rc, rt, root, comm);
}
int MPI_Gatherv(const void *sb, int sc, MPI_Datatype st, void *rb, const int *rc, const int *rd,
                MPI_Datatype rt, int root, MPI_Comm comm) {
  COUNT(GATHERV, (long long)sc * size_of(st));
  return PMPI_Gatherv(sb, sc, st, rb, rc, rd, rt, root, comm);
}
int MPI_Scan(const void *sb, void *rb, int c, MPI_Datatype t, MPI_Op op, MPI_Comm comm) {
  COUNT(SCAN, (long long)c * size_of(t));
  return PMPI_Scan(sb, rb, c, t, op, comm);
}
int MPI_Exscan(const void *sb, void *rb, int c, MPI_Datatype t, MPI_Op op, MPI_Comm comm) {
  COUNT(EXSCAN, (long long)c * size_of(t));
  return PMPI_Exscan(sb, rb, c, t, op, comm);
}
int MPI_Barrier(MPI_Comm comm) {
  COUNT(BARRIER, 0);
  return PMPI_Barrier(comm);
}
int MPI_Sendrecv(const void *sb, int sc, MPI_Datatype st, int dest, int stag, void *rb, int rc,
                 MPI_Datatype rt, int src, int rtag, MPI_Comm comm, MPI_Status *status) {
  COUNT(SENDRECV, (long long)sc * size_of(st));
  return PMPI_Sendrecv(sb, sc, st, dest, stag, rb, rc, rt, src, rtag, comm, status);
}
int MPI_Send(const void *b, int c, MPI_Datatype t, int dest, int tag, MPI_Comm comm) {
  COUNT(SEND, (long long)c * size_of(t));
  return PMPI_Send(b, c, t, dest, tag, comm);
}
int MPI_Isend(const void *b, int c, MPI_Datatype t, int dest, int tag, MPI_Comm comm,
              MPI_Request *req) {
  COUNT(ISEND, (long long)c * size_of(t));
  return PMPI_Isend(b, c, t, dest, tag, comm, req);
}
int MPI_Irecv(void *b, int c, MPI_Datatype t, int src, int tag, MPI_Comm comm,
              MPI_Request *req) {
  COUNT(IRECV, (long long)c * size_of(t)); /* (bytes received) */
  return PMPI_Irecv(b, c, t, src, tag, comm, req);
}
int MPI_Mprobe(int src, int tag, MPI_Comm comm, MPI_Message *m, MPI_Status *st) {
  COUNT(MPROBE, 0);
  return PMPI_Mprobe(src, tag, comm, m, st);
}
int MPI_Imrecv(void *b, int c, MPI_Datatype t, MPI_Message *m, MPI_Request *req) {
  COUNT(IMRECV, (long long)c * size_of(t)); /* (bytes received) */
  return PMPI_Imrecv(b, c, t, m, req);
}
/* One per halo exchange of parallel/exchange.cpp (each ends in one MPI_Waitall). */
int MPI_Waitall(int n, MPI_Request reqs[], MPI_Status st[]) {
  COUNT(WAITALL, 0);
  return PMPI_Waitall(n, reqs, st);
}
int MPI_Neighbor_alltoall(const void *sb, int sc, MPI_Datatype st, void *rb, int rc,
                          MPI_Datatype rt, MPI_Comm comm) {
  COUNT(NEIGHBOR_ALLTOALL, (long long)sc * size_of(st));
  return PMPI_Neighbor_alltoall(sb, sc, st, rb, rc, rt, comm);
}
int MPI_Neighbor_alltoallv(const void *sb, const int *sc, const int *sd, MPI_Datatype st,
                           void *rb, const int *rc, const int *rd, MPI_Datatype rt,
                           MPI_Comm comm) {
  COUNT(NEIGHBOR_ALLTOALLV, 0);
  return PMPI_Neighbor_alltoallv(sb, sc, sd, st, rb, rc, rd, rt, comm);
}
int MPI_Finalize(void) {
  const char *out = getenv("MPI_CALLS_OUT");
  int me = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &me);
  if (out) {
    FILE *f = fopen(out, "a");
    if (f) {
      fprintf(f, "%d", me);
      for (int k = 0; k < KINDS; ++k)
        fprintf(f, " %s %llu %llu", names[k], calls[k], bytes[k]);
      fprintf(f, "\n");
      fclose(f);
    }
  }
  return PMPI_Finalize();
}
