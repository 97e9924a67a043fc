/* Whole-process timing for the start-up benchmark (bench/run.sh, "Start-up"):
 * runs each command RUNS times (output to /dev/null), the commands taking
 * turns so that a change in the machine's load falls on all of them
 * alike, and prints per command, one line each, the median and the
 * smallest wall time in milliseconds, fork to exit. No library code: it
 * times the executables as a user runs them.
 * Usage: bench_startup RUNS COMMAND [ARGS...] [-- COMMAND [ARGS...]]...;
 * exit 1 when a run fails (exit code other than 0) or cannot start. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

#define MAX_CMDS 8

int main(int argc, char **argv) {
  int runs = argc > 2 ? atoi(argv[1]) : 0;
  if (runs < 1) {
    fprintf(stderr, "usage: bench_startup RUNS COMMAND [ARGS...] [-- COMMAND [ARGS...]]...\n");
    return 2;
  }
  /* split argv[2..] at "--" into commands (argv entries become their ends) */
  char **cmd[MAX_CMDS];
  int ncmd = 0;
  for (int i = 2; i < argc && ncmd < MAX_CMDS; i++) {
    if (i == 2 || !argv[i - 1]) cmd[ncmd++] = argv + i;
    if (!strcmp(argv[i], "--")) argv[i] = NULL;
  }
  double *t = malloc((size_t)(runs * ncmd) * sizeof *t);
  if (!t) return 2;
  for (int k = 0; k < runs; k++)
    for (int c = 0; c < ncmd; c++)
      if ((t[c * runs + k] = run_once(cmd[c])) < 0) {
        fprintf(stderr, "bench_startup: %s failed\n", cmd[c][0]);
        free(t);
        return 1;
      }
  for (int c = 0; c < ncmd; c++) {
    double *x = t + c * runs;
    qsort(x, (size_t)runs, sizeof *x, cmp);
    printf("%.3f %.3f\n", runs % 2 ? x[runs / 2] : (x[runs / 2 - 1] + x[runs / 2]) / 2, x[0]);
  }
  free(t);
  return 0;
}
