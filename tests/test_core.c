/* Tests of src/core: bitsets, the bitset hash set, the allocation funnel,
 * ids quoted for messages (text.c) and output files (file.c): a regular
 * file replaced with its mode kept, a hard-linked file written in place, a
 * symlink followed, a read-only file refused, an aborted write leaving the
 * old content, an output equal to an input refused. */
#define _XOPEN_SOURCE 700
#include "core/core.h"
#include "test.h"
#include "tmpfiles.h"

#include <sys/stat.h>
#include <unistd.h>

static void bitset_basics(void) {
  us_Bitset b;
  CHECK(us_bitset_init(&b, 130) == 0);
  CHECK_INT(us_bitset_count(&b), ==, 0);
  us_bitset_set(&b, 0);
  us_bitset_set(&b, 64);
  us_bitset_set(&b, 129);
  CHECK_INT(us_bitset_count(&b), ==, 3);
  CHECK(us_bitset_get(&b, 64) && !us_bitset_get(&b, 63));
  us_bitset_clear(&b, 64);
  CHECK_INT(us_bitset_count(&b), ==, 2);
  us_bitset_fill(&b);
  CHECK_INT(us_bitset_count(&b), ==, 130);
  us_Bitset c = {0};
  CHECK(us_bitset_copy(&c, &b) == 0);
  CHECK(us_bitset_equal(&b, &c));
  CHECK(us_bitset_hash(&b) == us_bitset_hash(&c));
  us_bitset_clear(&c, 7);
  CHECK(!us_bitset_equal(&b, &c));
  us_bitset_free(&b);
  us_bitset_free(&c);
}

/* us_bitset_next visits exactly the set bits, in order, against a plain
 * scan: sizes around word boundaries, random densities from empty to
 * full. */
static void bitset_next_matches_scan(void) {
  uint64_t x = 12345;
  int sizes[] = {1, 63, 64, 65, 127, 128, 129, 700};
  for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++)
    for (int density = 0; density <= 8; density++) {
      us_Bitset b;
      CHECK(us_bitset_init(&b, sizes[k]) == 0);
      for (int i = 0; i < sizes[k]; i++) {
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        if ((int)((x >> 33) % 8) < density) us_bitset_set(&b, i);
      }
      int i = us_bitset_next(&b, -1), seen = 0;
      for (int j = 0; j < sizes[k]; j++) {
        if (!us_bitset_get(&b, j)) continue;
        CHECK_INT(i, ==, j);
        i = us_bitset_next(&b, i);
        seen++;
      }
      CHECK_INT(i, ==, -1);
      CHECK_INT(seen, ==, us_bitset_count(&b));
      CHECK_INT(us_bitset_next(&b, sizes[k] - 1), ==, -1);
      us_bitset_free(&b);
    }
}

/* Insert many distinct subsets (more than 64 bits wide) and find each. */
static void bitset_set_many(void) {
  us_BitsetSet set;
  CHECK(us_bitset_set_init(&set, 200) == 0);
  us_Bitset b;
  CHECK(us_bitset_init(&b, 200) == 0);
  int n = 5000;
  for (int i = 0; i < n; i++) {
    memset(b.w, 0, (size_t)b.nwords * 8);
    us_bitset_set(&b, i % 200);
    us_bitset_set(&b, (i / 200) % 200);
    us_bitset_set(&b, 150 + (i / 40000));
    b.w[3] ^= (uint64_t)(i & 0xff);
    b.w[3] &= 0xff;
    int r = us_bitset_set_add(&set, &b);
    CHECK(r >= 0);
  }
  size_t count = set.count;
  CHECK(count > 1000);
  /* adding again adds nothing */
  for (int i = 0; i < n; i++) {
    memset(b.w, 0, (size_t)b.nwords * 8);
    us_bitset_set(&b, i % 200);
    us_bitset_set(&b, (i / 200) % 200);
    us_bitset_set(&b, 150 + (i / 40000));
    b.w[3] ^= (uint64_t)(i & 0xff);
    b.w[3] &= 0xff;
    CHECK(us_bitset_set_contains(&set, &b));
    CHECK_INT(us_bitset_set_add(&set, &b), ==, 0);
  }
  CHECK(set.count == count);
  memset(b.w, 0, (size_t)b.nwords * 8);
  us_bitset_set(&b, 199);
  us_bitset_set(&b, 198);
  us_bitset_set(&b, 197);
  CHECK(!us_bitset_set_contains(&set, &b));
  CHECK(us_bitset_set_bytes(&set) > 0);
  us_bitset_free(&b);
  us_bitset_set_free(&set);
}

static void alloc_failure_hook(void) {
  us_alloc_fail_after(1);
  void *a = us_malloc(8);
  void *b = us_malloc(8);
  us_alloc_fail_after(-1);
  CHECK(a != NULL);
  CHECK(b == NULL);
  us_free(a);
  /* the set reports OOM instead of crashing */
  us_BitsetSet set;
  us_alloc_fail_after(0);
  CHECK(us_bitset_set_init(&set, 10) == -1);
  us_alloc_fail_after(-1);
}

static void error_messages(void) {
  us_Error e;
  CHECK(us_error_set(&e, US_ERR_INPUT, "body '%s' bad", "b1") == US_ERR_INPUT);
  CHECK(strcmp(e.msg, "body 'b1' bad") == 0);
  CHECK(strcmp(us_status_name(US_ERR_NOMEM), "out of memory") == 0);
}

/* Escapes, a backslash doubled, no byte below 0x20 or ESC left, cuts at a
 * character boundary with "...". */
static void id_text(void) {
  CHECK(!strcmp(us_id_text("b1").s, "b1"));
  CHECK(!strcmp(us_id_text("a\x1b[31m\nb").s, "a\\x1B[31m\\x0Ab"));
  CHECK(!strcmp(us_id_text("x\\y").s, "x\\\\y"));
  CHECK(!strcmp(us_id_text("\xef\xbf\xbf\xc2\x85\xe2\x80\xae").s, "\\uFFFF\\u0085\\u202E"));
  CHECK(!strcmp(us_id_text("\xff\xc0\xaf\xed\xa0\x80").s, "\\xFF\\xC0\\xAF\\xED\\xA0\\x80"));
  CHECK(!strcmp(us_id_text("caf\xc3\xa9").s, "caf\xc3\xa9"));
  char longid[400] = "";
  for (int i = 0; i < 100; i++) strcat(longid, "\xc3\xa9"); /* 2-byte characters */
  longid[199] = 'x'; /* an odd length so that a byte cut would split one */
  us_IdText t = us_id_text(longid);
  size_t n = strlen(t.s);
  CHECK(n <= 83 && n >= 70);
  CHECK(!strcmp(t.s + n - 3, "..."));
  CHECK_INT((int)(n - 3) % 2, ==, 0); /* whole characters only */
  for (size_t k = 0; k + 3 < n; k += 2) CHECK(!memcmp(t.s + k, "\xc3\xa9", 2));
  char many_esc[200];
  memset(many_esc, 0x1b, sizeof many_esc - 1);
  many_esc[sizeof many_esc - 1] = 0;
  t = us_id_text(many_esc);
  CHECK(strlen(t.s) <= 83 && !strchr(t.s, 0x1b));
}


static us_Status put(const char *path, const char *text, us_Error *err) {
  us_AtomicFile *af = us_atomic_open(path, err);
  if (!af) return err->code;
  fputs(text, (FILE *)us_atomic_stream(af));
  return us_atomic_commit(af, err);
}

static int has(const char *path, const char *text) {
  char buf[64] = "";
  FILE *fp = fopen(path, "r");
  if (!fp) return 0;
  size_t n = fread(buf, 1, sizeof buf - 1, fp);
  fclose(fp);
  buf[n] = 0;
  return !strcmp(buf, text);
}

static int leftovers(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "ls %s | grep -q '\\.tmp\\.'", test_dir);
  return system(cmd) == 0;
}

/* New file, replaced file (mode kept), hard link (written in place, both
 * names see it), symlink (the link stays, the target changes), abort. */
static void output_files(void) {
  us_Error err;
  char a[128], b[128], l[128];
  CHECK(test_tmp_path("a.txt", a, sizeof a) && test_tmp_path("b.txt", b, sizeof b) &&
        test_tmp_path("l.txt", l, sizeof l));
  CHECK_OK(put(a, "one", &err), &err);
  CHECK(has(a, "one"));
  CHECK(chmod(a, 0640) == 0);
  CHECK_OK(put(a, "two", &err), &err);
  struct stat st;
  CHECK(stat(a, &st) == 0 && (st.st_mode & 07777) == 0640 && has(a, "two"));
  CHECK(link(a, b) == 0);
  CHECK_OK(put(b, "three", &err), &err);
  struct stat sa, sb;
  CHECK(stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_ino == sb.st_ino && sa.st_nlink == 2);
  CHECK(has(a, "three"));
  CHECK(symlink("a.txt", l) == 0);
  CHECK_OK(put(l, "four", &err), &err);
  CHECK(lstat(l, &st) == 0 && S_ISLNK(st.st_mode) && has(a, "four") && has(b, "four"));
  us_AtomicFile *af = us_atomic_open(a, &err);
  CHECK(af != NULL);
  fputs("partial", (FILE *)us_atomic_stream(af));
  us_atomic_abort(af);
  CHECK(has(a, "four"));
  CHECK(!leftovers());
  remove(l), remove(b), remove(a);
}

/* Read-only files (refused even for root: mode bits), directories, missing
 * directories, outputs that are inputs by another name. */
static void output_refusals(void) {
  us_Error err;
  char a[128], b[128], l[128], miss[160];
  CHECK(test_tmp_path("ro.txt", a, sizeof a) && test_tmp_path("h.txt", b, sizeof b) &&
        test_tmp_path("s.txt", l, sizeof l));
  snprintf(miss, sizeof miss, "%s/no/such/x.txt", test_dir);
  CHECK_OK(put(a, "keep", &err), &err);
  CHECK(chmod(a, 0444) == 0);
  CHECK(us_atomic_open(a, &err) == NULL && err.code == US_ERR_IO && strstr(err.msg, "not writable"));
  CHECK(us_output_check(a, NULL, 0, &err) == US_ERR_IO && strstr(err.msg, "not writable"));
  CHECK(has(a, "keep"));
  CHECK(chmod(a, 0644) == 0);
  CHECK(us_atomic_open(test_dir, &err) == NULL && strstr(err.msg, "is a directory"));
  CHECK(us_output_check(miss, NULL, 0, &err) == US_ERR_IO && strstr(err.msg, "cannot write"));
  CHECK(us_atomic_open(miss, &err) == NULL && err.code == US_ERR_IO);
  CHECK(link(a, b) == 0 && symlink("ro.txt", l) == 0);
  const char *inputs[1] = {a};
  CHECK(us_output_check(b, inputs, 1, &err) == US_ERR_IO &&
        strstr(err.msg, "output would overwrite input"));
  CHECK(us_output_check(l, inputs, 1, &err) == US_ERR_IO);
  char dotted[160];
  snprintf(dotted, sizeof dotted, "%s/./ro.txt", test_dir);
  CHECK(us_output_check(dotted, inputs, 1, &err) == US_ERR_IO);
  us_error_clear(&err);
  CHECK(us_output_check(miss, NULL, 0, NULL) == US_ERR_IO); /* NULL err is fine */
  char fresh[128];
  CHECK(test_tmp_path("fresh.txt", fresh, sizeof fresh));
  CHECK_OK(us_output_check(fresh, inputs, 1, &err), &err);
  CHECK(access(fresh, F_OK) != 0); /* the check touches nothing */
  remove(l), remove(b), remove(a);
}

/* Out of memory inside us_atomic_open fails cleanly, without a leak. */
static void output_nomem(void) {
  char a[128];
  CHECK(test_tmp_path("oom.txt", a, sizeof a));
  for (int n = 0; n < 4; n++) {
    us_Error err;
    us_alloc_fail_after(n);
    us_AtomicFile *af = us_atomic_open(a, &err);
    us_alloc_fail_after(-1);
    if (af) us_atomic_abort(af);
    else CHECK_INT(err.code, ==, US_ERR_NOMEM);
  }
  CHECK(!leftovers());
  CHECK(access(a, F_OK) != 0);
}

static void cleanup(void) {
  if (test_dir[0]) CHECK(rmdir(test_dir) == 0);
}

/* The id map against a linear search: random ids with repeats, from a
 * zeroed map through many doublings, every lookup and every refusal of a
 * repeated key as the reference says. */
static void idmap_matches_linear_search(void) {
  enum { N = 3000 };
  static char ids[N][12];
  unsigned long long rng = 5;
  us_IdMap m = {0, 0, NULL};
  int first[N], n = 0;
  for (int k = 0; k < N; k++) {
    snprintf(ids[k], sizeof ids[k], "b%d", (int)(test_rnd(&rng) * 2000));
    int want = -1;
    for (int q = 0; q < k && want < 0; q++)
      if (!strcmp(ids[q], ids[k])) want = first[q];
    first[k] = want >= 0 ? want : k;
    CHECK_INT(us_idmap_get(&m, ids[k]), ==, want);
    CHECK_INT(us_idmap_put(&m, ids[k], k), ==, want >= 0 ? -1 : 0);
    n += want < 0;
  }
  CHECK_INT(m.count, ==, n);
  for (int k = 0; k < N; k++) CHECK_INT(us_idmap_get(&m, ids[k]), ==, first[k]);
  CHECK_INT(us_idmap_get(&m, "b2000"), ==, -1);
  us_idmap_free(&m);
}

US_TEST_MAIN(T(bitset_basics), T(bitset_next_matches_scan), T(bitset_set_many), T(alloc_failure_hook), T(error_messages),
             T(id_text), T(output_files), T(output_refusals), T(output_nomem), T(cleanup),
             T(idmap_matches_linear_search))
