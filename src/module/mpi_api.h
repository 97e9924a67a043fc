/* The MPI module's entry points (src/module/mpi.c, modules/mpi.so): the few
 * MPI calls `unstack batch` makes when launched under mpirun, so that no
 * other command maps libmpi or pays its start-up (docs/batch.md). The
 * module is loaded with RTLD_GLOBAL, as Open MPI's own plugins need. */
#ifndef US_MODULE_MPI_API_H
#define US_MODULE_MPI_API_H

#define US_MPI_ABI 1

typedef struct us_MpiApi {
  int abi; /* US_MPI_ABI */
  /* MPI_Init; this rank and the number of ranks. 0 ok. */
  int (*init)(int *rank, int *size);
  /* Byte messages: blocking send; poll says whether a message from any
   * rank waits (1: its source, tag and length); probe waits for one from
   * src with tag and gives its length; recv takes it. 0 ok. */
  int (*send)(const void *buf, int n, int dest, int tag);
  int (*poll)(int *src, int *tag, int *n);
  int (*probe)(int src, int tag, int *n);
  int (*recv)(void *buf, int n, int src, int tag);
  void (*finalize)(void);
  void (*abort)(int code);
  /* The MPI library's own version line. */
  void (*version)(char *buf, int n);
} us_MpiApi;

typedef const us_MpiApi *(*us_MpiEntry)(void);

#endif
