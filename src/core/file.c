/* Output files that are never destroyed, and the clock.
 *
 * A writer gets a stream on a temporary file; commit puts the content in
 * place, abort throws it away, so a failed run never leaves a partial
 * output file. How the content is put in place depends on what the path
 * names (symlinks are resolved first, and the rules apply to the target):
 *   - nothing: a temp file in the same directory, renamed over the name
 *     (mode 0666 less umask), so the file appears complete or not at all;
 *   - a regular file with one link, in a writable directory: the same
 *     rename, with the old file's mode and ownership given to the new one;
 *   - anything else (a device such as /dev/null, a FIFO, a regular file
 *     with several hard links, one whose owner we cannot give back, one in
 *     a read-only directory): "copy mode". The content goes to an anonymous
 *     temp file (tmpfile) and is copied into the existing file at commit
 *     (open, truncate, write), so the file keeps its inode, its links, its
 *     mode and owner, and a device or FIFO is written through, never
 *     replaced. Only an I/O error during that final copy can leave it
 *     partial. A FIFO is opened at commit, which waits for a reader. Names
 *     under /dev and /proc are always written this way: /dev/stdout may
 *     lead to a regular file that the process itself holds open; a target
 *     that is the process's stdout or stderr is written through that
 *     descriptor, after what was printed before.
 * A regular file with no write bit is refused ("not writable") for every
 * user, root included: root passes access(2), so the mode bits are checked
 * too. Other permission checks use faccessat(AT_EACCESS), which root passes
 * as it passes the shell's own redirection.
 *
 * us_output_check runs the same checks without touching anything, plus a
 * comparison of the output's st_dev/st_ino with every input's, so that the
 * tool can refuse before a long computation starts. */
#define _XOPEN_SOURCE 700
#include "core.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

struct us_AtomicFile {
  FILE *fp;     /* where the writer writes */
  char *path;   /* the name given, for messages */
  char *target; /* the file renamed over or copied into */
  char *tmp;    /* named temp file (rename mode); NULL in copy mode */
};

/* the file a path designates: symlinks resolved when the target exists */
typedef struct {
  char target[PATH_MAX];
  struct stat st;
  int exists;
} Dest;

static us_Status io_fail(us_Error *err, const char *path, const char *what, int e) {
  return us_error_set(err, US_ERR_IO, "%s: %s: %s", path, what, strerror(e));
}

static us_Status resolve(const char *path, Dest *d, us_Error *err) {
  if (strlen(path) >= sizeof d->target)
    return us_error_set(err, US_ERR_IO, "%.200s...: path too long", path);
  strcpy(d->target, path);
  d->exists = stat(path, &d->st) == 0;
  if (d->exists) {
    /* a name realpath cannot spell (/dev/stdout on a pipe) is opened as given */
    if (!realpath(path, d->target)) strcpy(d->target, path);
    return US_OK;
  }
  if (errno == ENOENT) return US_OK; /* absent, or a symlink to nothing */
  return io_fail(err, path, "cannot write", errno);
}

static int is_symlink(const char *path) {
  struct stat st;
  return lstat(path, &st) == 0 && S_ISLNK(st.st_mode);
}

/* An existing destination may be written: not a directory, not a regular
 * file without write bits, and writable for the effective user. */
static us_Status check_existing(const char *path, const Dest *d, us_Error *err) {
  if (S_ISDIR(d->st.st_mode)) return us_error_set(err, US_ERR_IO, "%s: is a directory", path);
  if (S_ISREG(d->st.st_mode) && !(d->st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)))
    return us_error_set(err, US_ERR_IO, "%s: not writable (read-only file)", path);
  if (faccessat(AT_FDCWD, d->target, W_OK, AT_EACCESS) != 0)
    return io_fail(err, path, "not writable", errno);
  return US_OK;
}

/* The directory part of path, copied into buf ("." when there is none). */
static void dir_of(const char *path, char *buf, size_t cap) {
  const char *slash = strrchr(path, '/');
  size_t n = slash ? (size_t)(slash - path) : 0;
  if (slash && n == 0) n = 1; /* "/x" */
  if (!slash || n >= cap) n = 0;
  if (n) memcpy(buf, path, n);
  else strcpy(buf, ".");
  buf[n ? n : 1] = '\0';
}

static int dir_writable(const char *path) {
  char dir[PATH_MAX];
  dir_of(path, dir, sizeof dir);
  return faccessat(AT_FDCWD, dir, W_OK | X_OK, AT_EACCESS) == 0;
}

/* A new file: its directory must exist and be writable. */
static us_Status check_new(const char *path, const Dest *d, us_Error *err) {
  char dir[PATH_MAX];
  struct stat st;
  if (is_symlink(path)) return US_OK; /* dangling: the write creates the target */
  dir_of(d->target, dir, sizeof dir);
  int e = stat(dir, &st) != 0 ? errno : !S_ISDIR(st.st_mode) ? ENOTDIR : 0;
  if (!e && !dir_writable(d->target)) e = errno;
  if (e)
    return us_error_set(err, US_ERR_IO, "%s: cannot write in directory %s: %s", path, dir,
                        strerror(e));
  return US_OK;
}

us_Status us_output_check(const char *path, const char *const *inputs, int ninputs,
                          us_Error *err) {
  Dest d;
  us_Status st = resolve(path, &d, err);
  if (st) return st;
  if (!d.exists) return check_new(path, &d, err);
  for (int i = 0; i < ninputs; i++) {
    struct stat in;
    if (inputs[i] && stat(inputs[i], &in) == 0 && in.st_dev == d.st.st_dev &&
        in.st_ino == d.st.st_ino)
      return us_error_set(err, US_ERR_IO, "%s: output would overwrite input %s", path, inputs[i]);
  }
  return check_existing(path, &d, err);
}

/* rename mode: is the target a plain file we can replace without changing
 * anything but its content? */
static int can_rename(const char *path, const Dest *d) {
  if (!strncmp(path, "/dev/", 5) || !strncmp(path, "/proc/", 6)) return 0; /* /dev/stdout */
  if (!d->exists) return !is_symlink(path);
  return S_ISREG(d->st.st_mode) && d->st.st_nlink == 1 && dir_writable(d->target);
}

/* 0: af->fp is the named temp file; -1: cannot (copy mode for an existing
 * file); -2: out of memory. */
static int open_temp(us_AtomicFile *af, const Dest *d) {
  size_t n = strlen(af->target) + 16;
  if (!(af->tmp = us_malloc(n))) return -2;
  snprintf(af->tmp, n, "%s.tmp.XXXXXX", af->target);
  int fd = mkstemp(af->tmp);
  if (fd < 0) return -1;
  mode_t mode = d->exists ? d->st.st_mode & 07777 : 0;
  if (!d->exists) {
    mode_t mask = umask(0);
    umask(mask);
    mode = 0666 & ~mask;
  }
  int ok = fchmod(fd, mode) == 0;
  if (ok && d->exists && (d->st.st_uid != geteuid() || d->st.st_gid != getegid()))
    ok = fchown(fd, d->st.st_uid, d->st.st_gid) == 0;
  if (ok) af->fp = fdopen(fd, "w");
  if (!af->fp) close(fd), remove(af->tmp);
  return af->fp ? 0 : -1;
}

static void atomic_release(us_AtomicFile *af) {
  us_free(af->path);
  us_free(af->target);
  us_free(af->tmp);
  us_free(af);
}

us_AtomicFile *us_atomic_open(const char *path, us_Error *err) {
  Dest d;
  if (resolve(path, &d, err) ||
      (d.exists ? check_existing(path, &d, err) : check_new(path, &d, err)))
    return NULL;
  us_AtomicFile *af = us_calloc(1, sizeof *af);
  if (af) af->path = us_strdup(path);
  if (af && af->path) af->target = us_strdup(d.target);
  if (!af || !af->target) {
    if (af) atomic_release(af);
    us_error_set(err, US_ERR_NOMEM, "%s: out of memory", path);
    return NULL;
  }
  int r = can_rename(path, &d) ? open_temp(af, &d) : 1;
  if (r == -2 || (r == -1 && !d.exists)) {
    if (r == -2) us_error_set(err, US_ERR_NOMEM, "%s: out of memory", path);
    else io_fail(err, path, "cannot write", errno);
    atomic_release(af);
    return NULL;
  }
  if (!af->fp) { /* copy mode */
    us_free(af->tmp);
    af->tmp = NULL;
    af->fp = tmpfile();
  }
  if (!af->fp) {
    io_fail(err, path, "cannot create a temporary file", errno);
    atomic_release(af);
    return NULL;
  }
  return af;
}

void *us_atomic_stream(us_AtomicFile *af) { return af->fp; }

/* A descriptor on the target: the process's own stdout or stderr when the
 * target is the same file (-o /dev/stdout redirected to a file: a fresh open
 * would truncate it and write at offset 0 under the shell's output), else
 * the target opened for writing. */
static int open_target(const char *target) {
  struct stat t, o;
  int have = stat(target, &t) == 0;
  for (int fd = 1; have && fd <= 2; fd++)
    if (fstat(fd, &o) == 0 && o.st_dev == t.st_dev && o.st_ino == t.st_ino) {
      fflush(fd == 1 ? stdout : stderr);
      return dup(fd);
    }
  return open(target, O_WRONLY | O_CREAT | O_TRUNC | O_NOCTTY, 0666);
}

/* copy mode: the temp file's content into the existing target */
static int copy_into(us_AtomicFile *af) {
  if (fflush(af->fp) != 0 || fseek(af->fp, 0, SEEK_SET) != 0) return -1;
  int fd = open_target(af->target);
  if (fd < 0) return -1;
  char buf[1 << 14];
  size_t n;
  int bad = 0;
  while (!bad && (n = fread(buf, 1, sizeof buf, af->fp)) > 0)
    for (size_t off = 0; !bad && off < n;) {
      ssize_t w = write(fd, buf + off, n - off);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) bad = 1;
      else off += (size_t)w;
    }
  int e = errno;
  if (ferror(af->fp)) bad = 1;
  if (close(fd) != 0 && !bad) bad = 1, e = errno;
  errno = e;
  return bad ? -1 : 0;
}

us_Status us_atomic_commit(us_AtomicFile *af, us_Error *err) {
  int bad = ferror(af->fp) || fflush(af->fp) != 0;
  if (!bad && af->tmp) {
    if (fclose(af->fp) != 0) bad = 1;
    if (!bad && rename(af->tmp, af->target) != 0) bad = 1;
    if (bad) remove(af->tmp);
  } else {
    if (!bad && copy_into(af) != 0) bad = 1;
    int e = errno;
    fclose(af->fp);
    if (af->tmp) remove(af->tmp);
    errno = e;
  }
  us_Status st = bad ? io_fail(err, af->path, "cannot write", errno) : US_OK;
  atomic_release(af);
  return st;
}

void us_atomic_abort(us_AtomicFile *af) {
  if (!af) return;
  fclose(af->fp);
  if (af->tmp) remove(af->tmp);
  atomic_release(af);
}

double us_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
