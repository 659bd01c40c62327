/* igaparam_relocate_mpi: options, the serial run, and the partitioned run with its outputs. */

typedef struct {
  const char *input, *output, *gather;
  unsigned threads, max_sweeps;
  int serial;
} options;

static int parse(int argc, char **argv, options *o) {
  if (argc < 3) return 1;
  o->input = argv[1], o->output = argv[2];
  for (int i = 3; i < argc; ++i) {
    if (!strcmp(argv[i], "--gather") && i + 1 < argc) o->gather = argv[++i];
    else if (!strcmp(argv[i], "--threads") && i + 1 < argc) o->threads = (unsigned)strtoul(argv[++i], NULL, 10);
    else if (!strcmp(argv[i], "--max-sweeps") && i + 1 < argc) o->max_sweeps = (unsigned)strtoul(argv[++i], NULL, 10);
    else if (!strcmp(argv[i], "--serial")) o->serial = 1;
    else return 1;
  }
  return 0;
}

static void print_json(const igaparam_relocate_report *r, int ranks, double seconds,
                       double exchange_fraction, uint64_t sum) {
  printf("{\"ranks\": %d, \"cells\": %zu, \"nodes\": %zu, \"invalid_before\": %zu, "
         "\"invalid_after\": %zu, \"min_quality\": %.17g, \"mean_quality\": %.17g, \"sweeps\": %u, "
         "\"steps\": %u, \"seconds\": %.6f, \"exchange_fraction\": %.4f, \"checksum\": \"%016llx\"}\n",
         ranks, r->cells, r->nodes, r->invalid_before, r->invalid_after, r->min_quality,
         r->mean_quality, r->sweeps, r->steps, seconds, exchange_fraction, (unsigned long long)sum);
}

/* The whole mesh relocated in one process by the sweeps (rank 0 only). */
static int run_serial(whole_mesh *w, const options *o, int rank) {
  if (rank != 0) return 0;
  igaparam_relocate_options opt = igaparam_relocate_options_default();
  opt.method = IGAPARAM_METHOD_SWEEPS;
  opt.threads = o->threads;
  if (o->max_sweeps) opt.max_sweeps = o->max_sweeps;
  igaparam_relocate_report r;
  igaparam_status st = igaparam_mesh_relocate(w->mesh, &opt, &r);
  if (st != IGAPARAM_STATUS_OK) return fail("igaparam_mesh_relocate", st);
  double *x = checked_malloc(3 * w->nodes * sizeof(double));
  igaparam_mesh_copy_positions(w->mesh, x, 3 * w->nodes);
  print_json(&r, 1, r.seconds, 0.0, checksum(x, 3 * w->nodes));
  free(x);
  return r.invalid_after == 0 ? 0 : 1;
}

/* A rank's part: local nodes (global ids), their ownership, local cells. */
typedef struct {
  size_t nodes, cells, core;
  int64_t *gid, *cell_gid, *conn;
  uint8_t *owned;
  double *reference, *moved;
  uint8_t *fixed;
} part;

/* Builds this rank's part from the cell ranks of the bisection. */
static void make_part(const whole_mesh *w, const int *rank_of, int rank, part *p) {
  int *owner = checked_malloc(w->nodes * sizeof(int));
  for (size_t v = 0; v < w->nodes; ++v) owner[v] = INT_MAX;
  for (size_t c = 0; c < w->cells; ++c)
    for (size_t i = 0; i < w->per; ++i) {
      int64_t v = w->conn[c * w->per + i];
      if (rank_of[c] < owner[v]) owner[v] = rank_of[c];
    }
  for (size_t v = 0; v < w->nodes; ++v)
    if (owner[v] == INT_MAX) owner[v] = 0; /* nodes in no cell */
  /* Local cells: this rank's own (first) and those around its nodes. */
  char *take = checked_malloc(w->cells);
  p->cells = p->core = 0;
  for (size_t c = 0; c < w->cells; ++c) {
    take[c] = rank_of[c] == rank;
    for (size_t i = 0; i < w->per && !take[c]; ++i) take[c] = owner[w->conn[c * w->per + i]] == rank;
    p->cells += take[c];
    p->core += rank_of[c] == rank;
  }
  int64_t *local = checked_malloc(w->nodes * sizeof(int64_t));
  for (size_t v = 0; v < w->nodes; ++v) local[v] = owner[v] == rank ? 0 : -1;
  for (size_t c = 0; c < w->cells; ++c)
    for (size_t i = 0; i < w->per && take[c]; ++i) local[w->conn[c * w->per + i]] = 0;
  p->nodes = 0;
  for (size_t v = 0; v < w->nodes; ++v)
    if (local[v] == 0) local[v] = (int64_t)p->nodes++;
  p->gid = checked_malloc(p->nodes * sizeof(int64_t));
  p->owned = checked_malloc(p->nodes);
  p->fixed = checked_malloc(p->nodes);
  p->reference = checked_malloc(3 * p->nodes * sizeof(double));
  p->moved = checked_malloc(3 * p->nodes * sizeof(double));
  for (size_t v = 0; v < w->nodes; ++v) {
    if (local[v] < 0) continue;
    size_t l = (size_t)local[v];
    p->gid[l] = (int64_t)v, p->owned[l] = owner[v] == rank, p->fixed[l] = w->fixed[v];
    memcpy(p->reference + 3 * l, w->reference + 3 * v, 3 * sizeof(double));
    memcpy(p->moved + 3 * l, w->moved + 3 * v, 3 * sizeof(double));
  }
  p->cell_gid = checked_malloc(p->cells * sizeof(int64_t));
  p->conn = checked_malloc(p->cells * w->per * sizeof(int64_t));
  size_t k = 0;
  for (int pass = 0; pass < 2; ++pass) /* own cells first: they form the written piece */
    for (size_t c = 0; c < w->cells; ++c) {
      if (!take[c] || (rank_of[c] == rank) != (pass == 0)) continue;
      p->cell_gid[k] = (int64_t)c;
      for (size_t i = 0; i < w->per; ++i) p->conn[k * w->per + i] = local[w->conn[c * w->per + i]];
      ++k;
    }
  free(owner), free(take), free(local);
}

/* Writes this rank's own cells as a .vtu piece (unused nodes and all, as in the part). */
static int write_piece(const whole_mesh *w, const part *p, const double *x, const char *path) {
  igaparam_mesh *m = NULL;
  igaparam_status st = igaparam_mesh_new(w->type, p->nodes, p->reference, p->core, p->conn, &m);
  if (st == IGAPARAM_STATUS_OK) st = igaparam_mesh_set_fixed(m, p->nodes, p->fixed);
  if (st == IGAPARAM_STATUS_OK) st = igaparam_mesh_move_nodes(m, p->nodes, NULL, x);
  if (st == IGAPARAM_STATUS_OK) st = igaparam_mesh_write_vtu(m, path);
  igaparam_mesh_free(m);
  return st == IGAPARAM_STATUS_OK ? 0 : fail("writing the piece", st);
}

/* OUT.pvtu's pieces are OUT_<rank>.vtu, next to it. */
static void piece_path(const char *pvtu, int rank, char *out, size_t len, int base_only) {
  const char *name = base_only && strrchr(pvtu, '/') ? strrchr(pvtu, '/') + 1 : pvtu;
  size_t n = strlen(name);
  if (n > 5 && !strcmp(name + n - 5, ".pvtu")) n -= 5;
  snprintf(out, len, "%.*s_%d.vtu", (int)n, name, rank);
}

static int write_pvtu(const char *path, int ranks) {
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "igaparam_relocate_mpi: cannot write %s\n", path);
    return 1;
  }
  fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n"
             "    <PPointData>\n      <PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>\n"
             "      <PDataArray type=\"UInt8\" Name=\"fixed_components\" NumberOfComponents=\"1\"/>\n"
             "    </PPointData>\n    <PCellData>\n"
             "      <PDataArray type=\"Float64\" Name=\"quality\" NumberOfComponents=\"1\"/>\n    </PCellData>\n"
             "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n    </PPoints>\n");
  for (int r = 0; r < ranks; ++r) {
    char piece[4096];
    piece_path(path, r, piece, sizeof piece, 1);
    fprintf(f, "    <Piece Source=\"%s\"/>\n", piece);
  }
  fprintf(f, "  </PUnstructuredGrid>\n</VTKFile>\n");
  return fclose(f) == 0 ? 0 : 1;
}

/* Rank 0 gets every owned position, in input order. */
static double *gather_whole(const whole_mesh *w, const part *p, const double *x, MPI_Comm comm, int rank, int size) {
  int mine = 0;
  for (size_t v = 0; v < p->nodes; ++v) mine += p->owned[v];
  double *send = checked_malloc(4 * (size_t)mine * sizeof(double));
  for (size_t v = 0, k = 0; v < p->nodes; ++v)
    if (p->owned[v]) {
      send[4 * k] = (double)p->gid[v];
      memcpy(send + 4 * k + 1, x + 3 * v, 3 * sizeof(double));
      ++k;
    }
  int *counts = checked_malloc(2 * sizeof(int) * (size_t)size), *displs = counts + size;
  int n4 = 4 * mine;
  MPI_Gather(&n4, 1, MPI_INT, counts, 1, MPI_INT, 0, comm);
  double *all = NULL, *whole = NULL;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) displs[r] = total, total += counts[r];
    all = checked_malloc((size_t)total * sizeof(double));
    whole = checked_malloc(3 * w->nodes * sizeof(double));
    memcpy(whole, w->moved, 3 * w->nodes * sizeof(double));
  }
  MPI_Gatherv(send, n4, MPI_DOUBLE, all, counts, displs, MPI_DOUBLE, 0, comm);
  if (rank == 0) {
    for (size_t i = 0; i < w->nodes; ++i) {
      size_t v = (size_t)all[4 * i];
      memcpy(whole + 3 * v, all + 4 * i + 1, 3 * sizeof(double));
    }
  }
  free(send), free(counts), free(all);
  return whole;
}

static int run_parts(whole_mesh *w, const options *o, MPI_Comm comm, int rank, int size) {
  double *centres = checked_malloc(3 * w->cells * sizeof(double));
  size_t *cells = checked_malloc(w->cells * sizeof(size_t));
  int *rank_of = checked_malloc(w->cells * sizeof(int));
  for (size_t c = 0; c < w->cells; ++c) {
    cells[c] = c;
    for (int k = 0; k < 3; ++k) {
      double s = 0;
      for (size_t i = 0; i < w->per; ++i) s += w->reference[3 * w->conn[c * w->per + i] + k];
      centres[3 * c + k] = s / (double)w->per;
    }
  }
  bisect(centres, cells, w->cells, 0, size, rank_of);
  part p;
  make_part(w, rank_of, rank, &p);
  free(centres), free(cells), free(rank_of);
  igaparam_exchange ex = {rank, size, exchange_mpi, &comm};
  igaparam_partition *h = NULL;
  igaparam_status st = igaparam_partition_new(&ex, w->type, p.nodes, p.gid, p.owned, p.reference,
                                              p.cells, p.cell_gid, p.conn, &h);
  if (st != IGAPARAM_STATUS_OK) return fail("igaparam_partition_new", st);
  igaparam_partition_set_fixed(h, p.nodes, p.fixed);
  igaparam_partition_set_positions(h, 3 * p.nodes, p.moved);
  igaparam_relocate_options opt = igaparam_relocate_options_default();
  opt.method = IGAPARAM_METHOD_SWEEPS;
  opt.threads = o->threads;
  if (o->max_sweeps) opt.max_sweeps = o->max_sweeps;
  igaparam_partition_report r;
  MPI_Barrier(comm);
  double t0 = MPI_Wtime();
  st = igaparam_partition_relocate(h, &ex, &opt, &r);
  double seconds = MPI_Wtime() - t0;
  if (st != IGAPARAM_STATUS_OK) {
    igaparam_partition_free(h);
    return fail("igaparam_partition_relocate", st);
  }
  double *x = checked_malloc(3 * p.nodes * sizeof(double));
  igaparam_partition_copy_positions(h, x, 3 * p.nodes);
  igaparam_partition_free(h);
  double fraction = r.exchange_seconds / (seconds > 0 ? seconds : 1), max_fraction = 0, max_seconds = 0;
  MPI_Reduce(&fraction, &max_fraction, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  MPI_Reduce(&seconds, &max_seconds, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  char piece[4096];
  piece_path(o->output, rank, piece, sizeof piece, 0);
  int code = write_piece(w, &p, x, piece);
  if (rank == 0 && code == 0) code = write_pvtu(o->output, size);
  double *whole = gather_whole(w, &p, x, comm, rank, size);
  if (rank == 0) {
    if (o->gather && code == 0) {
      st = igaparam_mesh_move_nodes(w->mesh, w->nodes, NULL, whole);
      if (st == IGAPARAM_STATUS_OK) st = igaparam_mesh_write_vtu(w->mesh, o->gather);
      if (st != IGAPARAM_STATUS_OK) code = fail("writing the whole mesh", st);
    }
    print_json(&r.relocation, size, max_seconds, max_fraction, checksum(whole, 3 * w->nodes));
    if (r.relocation.invalid_after != 0) code = 1;
  }
  free(x), free(whole);
  return code;
}
