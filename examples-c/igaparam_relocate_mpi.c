/*
 * igaparam_relocate_mpi: relocation of a mesh partitioned over the ranks of an MPI job.
 *
 *   mpirun -np N igaparam_relocate_mpi IN.vtu OUT.pvtu [--gather WHOLE.vtu] [--threads T]
 *                                      [--max-sweeps S]
 *   igaparam_relocate_mpi IN.vtu - --serial [--threads T] [--max-sweeps S]   (one process)
 *
 * Every rank reads IN (with its point arrays `fixed_components` and `moved`, as relocate_vtu),
 * partitions the cells by recursive coordinate bisection of their centres, builds its part
 * (its cells plus the cells around the nodes it owns, a node being owned by the lowest rank
 * among those whose cells hold it), and all ranks relocate together through an exchange
 * callback over MPI_COMM_WORLD. Each rank writes its cells as OUT_<rank>.vtu and rank 0 writes
 * OUT.pvtu, which opens the whole in ParaView; --gather also writes the whole relocated mesh in
 * the input's node order. Rank 0 prints one JSON object: the relocation's figures, the time and
 * the largest fraction of it spent in exchanges, and `checksum`, an FNV-1a hash of the bits of
 * all positions in input order. --serial relocates the whole mesh with igaparam_mesh_relocate
 * and IGAPARAM_METHOD_SWEEPS and prints the same figures: the checksums must agree.
 */

#include <limits.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "igaparam.h"

/* The whole mesh as read. */
typedef struct {
  igaparam_mesh *mesh;
  igaparam_cell_type type;
  size_t nodes, cells, per;
  double *reference, *moved;
  uint8_t *fixed;
  int64_t *conn;
} whole_mesh;

static int fail(const char *what, igaparam_status status) {
  char message[2048];
  igaparam_last_error_message(message, sizeof message);
  fprintf(stderr, "igaparam_relocate_mpi: %s failed (status %d): %s\n", what, (int)status, message);
  return 1;
}

static void *checked_malloc(size_t n) {
  void *p = malloc(n ? n : 1);
  if (!p) {
    fprintf(stderr, "igaparam_relocate_mpi: out of memory\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return p;
}

/* MPI_Alltoallv of bytes over the communicator `user`. */
static int exchange_mpi(void *user, const size_t *send_counts, const unsigned char *send,
                        const size_t *recv_counts, unsigned char *recv) {
  MPI_Comm comm = *(MPI_Comm *)user;
  int p;
  MPI_Comm_size(comm, &p);
  int *sc = checked_malloc(4 * sizeof(int) * (size_t)p), *sd = sc + p, *rc = sd + p, *rd = rc + p;
  size_t s = 0, r = 0;
  for (int i = 0; i < p; ++i) {
    if (send_counts[i] > INT_MAX || recv_counts[i] > INT_MAX || s > INT_MAX || r > INT_MAX) {
      free(sc);
      return -1;
    }
    sc[i] = (int)send_counts[i], sd[i] = (int)s, rc[i] = (int)recv_counts[i], rd[i] = (int)r;
    s += send_counts[i], r += recv_counts[i];
  }
  int code = MPI_Alltoallv(send, sc, sd, MPI_BYTE, recv, rc, rd, MPI_BYTE, comm);
  free(sc);
  return code == MPI_SUCCESS ? 0 : code;
}

static int read_whole(const char *path, whole_mesh *w) {
  igaparam_status st = igaparam_mesh_read_vtu(path, &w->mesh);
  if (st != IGAPARAM_STATUS_OK) return fail("igaparam_mesh_read_vtu", st);
  igaparam_mesh_node_count(w->mesh, &w->nodes);
  igaparam_mesh_cell_count(w->mesh, &w->cells);
  igaparam_mesh_cell_type(w->mesh, &w->type);
  igaparam_cell_type_node_count(w->type, &w->per);
  w->reference = checked_malloc(3 * w->nodes * sizeof(double));
  w->moved = checked_malloc(3 * w->nodes * sizeof(double));
  w->fixed = checked_malloc(w->nodes);
  w->conn = checked_malloc(w->cells * w->per * sizeof(int64_t));
  igaparam_mesh_copy_reference(w->mesh, w->reference, 3 * w->nodes);
  igaparam_mesh_copy_positions(w->mesh, w->moved, 3 * w->nodes);
  igaparam_mesh_copy_fixed(w->mesh, w->fixed, w->nodes);
  igaparam_mesh_copy_connectivity(w->mesh, IGAPARAM_ORDER_VTK, w->conn, w->cells * w->per);
  return 0;
}

/* Cell centres for the bisection, with the cell's index as the tie-break. */
static const double *sort_centres;
static int sort_axis;
static int by_centre(const void *a, const void *b) {
  size_t i = *(const size_t *)a, j = *(const size_t *)b;
  double x = sort_centres[3 * i + sort_axis], y = sort_centres[3 * j + sort_axis];
  return x < y ? -1 : x > y ? 1 : (i > j) - (i < j);
}

/* Assigns cells[0..n) to ranks first..first+ranks-1 by recursive coordinate bisection. */
static void bisect(const double *centres, size_t *cells, size_t n, int first, int ranks, int *rank_of) {
  if (ranks == 1 || n == 0) {
    for (size_t i = 0; i < n; ++i) rank_of[cells[i]] = first;
    return;
  }
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      double x = centres[3 * cells[i] + k];
      lo[k] = x < lo[k] ? x : lo[k], hi[k] = x > hi[k] ? x : hi[k];
    }
  sort_axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[sort_axis] - lo[sort_axis]) sort_axis = k;
  sort_centres = centres;
  qsort(cells, n, sizeof(size_t), by_centre);
  int left = ranks / 2;
  size_t split = n * (size_t)left / (size_t)ranks;
  bisect(centres, cells, split, first, left, rank_of);
  bisect(centres, cells + split, n - split, first + left, ranks - left, rank_of);
}

/* FNV-1a over the bytes of the doubles. */
static uint64_t checksum(const double *x, size_t n) {
  uint64_t h = 1469598103934665603ULL;
  const unsigned char *b = (const unsigned char *)x;
  for (size_t i = 0; i < n * sizeof(double); ++i) h = (h ^ b[i]) * 1099511628211ULL;
  return h;
}

#include "relocate_mpi_parts.h"

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  options o = {0};
  if (parse(argc, argv, &o) != 0) {
    if (rank == 0)
      fprintf(stderr, "usage: igaparam_relocate_mpi IN.vtu OUT.pvtu [--gather WHOLE.vtu] [--threads N]"
                      " [--max-sweeps S] | IN.vtu - --serial [--threads N] [--max-sweeps S]\n");
    MPI_Finalize();
    return 2;
  }
  whole_mesh w;
  int code = read_whole(o.input, &w);
  int any = 0;
  MPI_Allreduce(&code, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any == 0) code = o.serial ? run_serial(&w, &o, rank) : run_parts(&w, &o, comm, rank, size);
  MPI_Allreduce(&code, &any, 1, MPI_INT, MPI_MAX, comm);
  MPI_Finalize();
  return any;
}
