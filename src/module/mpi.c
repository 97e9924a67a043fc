/* The MPI module (modules/mpi.so): thin wrappers over the MPI calls of
 * `unstack batch` under mpirun (tools/batch_mpi.c), byte messages between
 * ranks of MPI_COMM_WORLD. Only batch loads it, only under a launcher. */
#include "module/mpi_api.h"

#include <mpi.h>
#include <string.h>

static int init(int *rank, int *size) {
  if (MPI_Init(NULL, NULL) != MPI_SUCCESS) return -1;
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return 0;
}

static int send(const void *buf, int n, int dest, int tag) {
  return MPI_Send(buf, n, MPI_BYTE, dest, tag, MPI_COMM_WORLD) != MPI_SUCCESS;
}

static int poll_any(int *src, int *tag, int *n) {
  int flag = 0;
  MPI_Status st;
  if (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st) != MPI_SUCCESS || !flag)
    return 0;
  *src = st.MPI_SOURCE, *tag = st.MPI_TAG;
  MPI_Get_count(&st, MPI_BYTE, n);
  return 1;
}

static int probe(int src, int tag, int *n) {
  MPI_Status st;
  if (MPI_Probe(src, tag, MPI_COMM_WORLD, &st) != MPI_SUCCESS) return -1;
  return MPI_Get_count(&st, MPI_BYTE, n) != MPI_SUCCESS;
}

static int recv(void *buf, int n, int src, int tag) {
  return MPI_Recv(buf, n, MPI_BYTE, src, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS;
}

static void finalize(void) { MPI_Finalize(); }
static void abort_all(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

static void version(char *buf, int n) {
  char v[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(v, &len);
  v[len < (int)sizeof v ? len : (int)sizeof v - 1] = '\0';
  char *nl = strchr(v, ',');
  if (nl) *nl = '\0'; /* "Open MPI v4.1.4, package: ..." */
  if (n > 0) strncpy(buf, v, (size_t)n - 1), buf[n - 1] = '\0';
}

__attribute__((visibility("default"))) const us_MpiApi *us_module_mpi(void);
const us_MpiApi *us_module_mpi(void) {
  static const us_MpiApi api = {US_MPI_ABI, init, send, poll_any, probe, recv,
                                finalize, abort_all, version};
  return &api;
}
