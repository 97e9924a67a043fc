/* Whole-process timing for the start-up benchmark (bench/run.sh, "Start-up"):
 * runs a command RUNS times (output to /dev/null) and prints the median and
 * the smallest wall time in milliseconds, fork to exit. No library code: it
 * times the executable as a user runs it.
 * Usage: bench_startup RUNS COMMAND [ARGS...]; exit 1 when a run fails
 * (exit code other than 0) or cannot start. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* One run: its wall time in ms, or a negative number when it failed. */
static double run_once(char **argv) {
  double t0 = now_ms();
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 1);
      dup2(null, 2);
    }
    execvp(argv[0], argv);
    _exit(127);
  }
  int status;
  if (waitpid(pid, &status, 0) != pid) return -1;
  double t = now_ms() - t0;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? t : -1;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  int runs = argc > 2 ? atoi(argv[1]) : 0;
  if (runs < 1) {
    fprintf(stderr, "usage: bench_startup RUNS COMMAND [ARGS...]\n");
    return 2;
  }
  double *t = malloc((size_t)runs * sizeof *t);
  if (!t) return 2;
  for (int k = 0; k < runs; k++)
    if ((t[k] = run_once(argv + 2)) < 0) {
      fprintf(stderr, "bench_startup: %s failed\n", argv[2]);
      free(t);
      return 1;
    }
  qsort(t, (size_t)runs, sizeof *t, cmp);
  printf("%.3f %.3f\n", runs % 2 ? t[runs / 2] : (t[runs / 2 - 1] + t[runs / 2]) / 2, t[0]);
  free(t);
  return 0;
}
