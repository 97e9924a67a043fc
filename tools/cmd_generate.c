/* unstack generate: write a generated structure (column, pyramid, wall,
 * arch, random, stacker; in 3D tower, pyramid3d, wall3d, dome, jenga,
 * random3d) as a structure file. */
#define _POSIX_C_SOURCE 200809L
#include "options.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char head[] =
    "usage: unstack generate KIND [options] -o FILE\n"
    "\n"
    "kinds and their options:\n"
    "  column   --blocks N                    N blocks stacked on the ground\n"
    "  pyramid  --rows N                      stack bond, N rows (13 rows = 91 blocks)\n"
    "  wall     --rows R --cols C             running bond with half bricks at the ends\n"
    "  arch     --voussoirs N --radius R --thickness T [--loose K: K unit blocks\n"
    "           on the ground beside it]\n"
    "                                         semicircular, radial joints, on the ground\n"
    "  random   --rows R --width W --seed S   the random stacker: blocks 1 wide dropped at\n"
    "                                         random rows and offsets (quarter blocks) in a\n"
    "                                         width of W blocks (default 5), kept only if all\n"
    "                                         still stands, until row R is reached\n"
    "  stacker  --rows R --width W --seed S  the source-style stacker: rows of blocks 1 to 2\n"
    "                                         wide at quarter-block offsets in a width of W\n"
    "                                         blocks (default 12); 10-18 % are cantilevers held\n"
    "                                         by a counterweight in the row above, so only the\n"
    "                                         finished structure stands (14 x 12: ~75 blocks,\n"
    "                                         60 x 60: ~1,000)\n"
    "\n"
    "3D kinds (\"dimension\": 3, z up):\n"
    "  tower     --blocks N [--jitter DEG --seed S]\n"
    "                                         N boxes stacked on one vertical axis, each\n"
    "                                         turned about it by up to DEG degrees\n"
    "  pyramid3d --rows N                     square courses in stack bond, each offset by\n"
    "                                         half a block in x and y (N(N+1)(2N+1)/6 boxes)\n"
    "  wall3d    --rows R --cols C [--thickness T] [--returns L]\n"
    "                                         the running-bond wall with bricks T deep (0.5);\n"
    "                                         --returns adds at both ends a return wall of L\n"
    "                                         bricks' length (outer face) along +y, bonded at\n"
    "                                         the corner: the main wall's corner brick runs\n"
    "                                         through in courses 1, 3, ..., the return's in\n"
    "                                         2, 4, ...; needs T < block width (0: straight)\n"
    "  dome      --courses N --segments M --radius R --thickness T --oculus DEG [--cap]\n"
    "            [--chamfer F]\n"
    "                                         a hemispherical dome of N courses (10) of M\n"
    "                                         voussoirs (12) on the ground, inner radius R (3),\n"
    "                                         T thick (0.5), open at the top DEG degrees from\n"
    "                                         the vertical (15); --cap closes the opening with\n"
    "                                         one keystone; --chamfer bevels the voussoirs'\n"
    "                                         lower side edges by F of their width and course\n"
    "                                         height (0: sharp; docs/format.md: why sharp\n"
    "                                         edges let it plan one voussoir at a time)\n"
    "  jenga     --levels N [--remove L:P,L:P...]\n"
    "                                         N levels (10) of 3 pieces 3 x 1 x 0.6 block\n"
    "                                         widths, alternating direction; --remove leaves\n"
    "                                         out piece P (1, 3 the sides, 2 the middle) of\n"
    "                                         level L (1 = on the ground)\n"
    "  random3d  --blocks N --width W --seed S\n"
    "                                         unit boxes dropped at random (quarter steps) on\n"
    "                                         a W x W area (default 4), each resting on the\n"
    "                                         highest boxes under it, kept only if all still\n"
    "                                         stands; stops at N boxes (10) or after\n"
    "                                         --max-tries discarded drops in a row (fewer)\n";
static const char tail[] =
    "exit: 0 written, 2 usage error (nothing written), 3 stopped by --time-limit (nothing\n"
    "written)\n";

typedef us_GenFn GenFn;

/* Options that are not plain settings, and which defaults were overridden. */
typedef struct Extra {
  double rand_width;  /* --width, 0 when not given */
  const char *remove; /* --remove list, NULL when not given */
  int height_given, tries_given;
  int returns_given; /* --returns, for wall3d only */
  double time_limit;  /* --time-limit, 0 when not given */
  int count;          /* --count N: N files into the directory -o DIR/, 0: one file */
} Extra;

/* A positive int setting: "--blocks N" ... */
#define GEN_INT(n, v, d, h, ...) CLI_INT(n, v, d, h, CLI_ATLEAST(1), __VA_ARGS__)

/* The command line after KIND, by generate's option table (optable.h);
 * argc 0: print the help on stderr (no KIND given) and return CLI_EXIT_ERR. */
static int parse(int argc, char **argv, us_GenSettings *g, Extra *x, const char **out) {
  /* One entry per option, in --help's order; optable.h says how to add one. */
  const CliOpt opts[] = {
      CLI_TEXT("--output", "FILE", out, "structure file to write (required); with --count a "
               "directory (created if missing)", .alias = "-o"),
      CLI_INT("--count", "N", &x->count, "write N structures with consecutive seeds S, S+1, ... "
              "into the directory -o DIR/, named KIND-SEED.json (seeds zero-padded to one width)",
              CLI_ATLEAST(1)),
      GEN_INT("--blocks", "N", &g->n, "column, tower: blocks; random3d: boxes (default 10)"),
      GEN_INT("--rows", "N", &g->rows, "pyramid, pyramid3d, wall, wall3d, random, stacker: rows (default 10)"),
      GEN_INT("--cols", "C", &g->cols, "wall, wall3d: bricks per course (default 10)"),
      GEN_INT("--voussoirs", "N", &g->n, "arch: voussoirs (default 10)"),
      GEN_INT("--courses", "N", &g->n, "dome: courses (default 10)"),
      GEN_INT("--segments", "M", &g->segments, "dome: voussoirs per course (default 12)"),
      GEN_INT("--levels", "N", &g->n, "jenga: levels (default 10)"),
      GEN_INT("--loose", "K", &g->loose, "arch: K unit blocks on the ground beside it (default none)"),
      CLI_REAL("--radius", "R", &g->radius, "arch, dome: (inner) radius (default 3)"),
      CLI_REAL("--thickness", "T", &g->thickness, "arch, dome: thickness; wall3d: brick depth "
               "(default 0.5)"),
      CLI_REAL("--oculus", "DEG", &g->oculus, "dome: opening at the top, degrees from the "
               "vertical (default 15)"),
      CLI_FLAG("--cap", &g->cap, "dome: close the opening with one keystone"),
      CLI_REAL("--chamfer", "F", &g->chamfer, "dome: bevel of the voussoirs' lower side edges, a fraction "
               "of their width and course height (default 0.02; 0: sharp)"),
      CLI_INT("--returns", "L", &g->returns, "wall3d: return walls of L bricks at both ends (default 0)",
              CLI_ATLEAST(0), .need = "a non-negative integer (bricks)",
              .given = &x->returns_given),
      CLI_TEXT("--remove", "L:P,...", &x->remove, "jenga: pieces left out"),
      CLI_REAL("--jitter", "DEG", &g->jitter, "tower: largest turn of a box about the vertical (default 0)"),
      CLI_REAL("--width", "W", &x->rand_width, "random, stacker, random3d: structure width in "
               "blocks (default 5, 12, 4)", CLI_POSITIVE, .need = "a positive number"),
      CLI_ULONG("--seed", "S", &g->seed, "random, stacker, tower, random3d: seed (default 1)",
                CLI_ATLEAST(0)),
      CLI_REAL("--block-width", "X", &g->width, "block width (default 1; not for random, "
               "stacker, random3d)"),
      CLI_REAL("--block-height", "Y", &g->height, "block height (default 0.5; jenga 0.6)",
               .given = &x->height_given),
      CLI_REAL("--block-depth", "D", &g->depth, "3D block depth along y (tower, pyramid3d; "
               "default 1)"),
      CLI_REAL("--friction", "MU", &g->friction, "Coulomb coefficient written to the file "
               "(default 0.5; 'infinite': no sliding)", .inf_ok = 1),
      CLI_REAL("--density", "D", &g->density, "density of every block (default 1)"),
      GEN_INT("--max-tries", "N", &g->max_tries, "random, stacker: attempts before giving up "
              "(default 10000); random3d: discarded drops in a row before stopping (200)",
              .given = &x->tries_given),
      CLI_OPT_TIME_LIMIT(&x->time_limit,
                         "stop after S seconds (stacker, random3d: between steps and in "
                         "their stability tests; random: between attempts; every kind: "
                         "finding contacts), nothing written, exit 3"),
      CLI_END};
  const CliSpec spec = {"generate", head, tail, opts, NULL, 0, NULL};
  if (argc == 0) return cli_print_help(&spec, stderr), CLI_EXIT_ERR;
  return cli_parse(&spec, argc, argv);
}

/* Parse "L:P,L:P,..." into pairs (*out, 2 ints a piece; freed by the
 * caller) for jenga's remove list. */
static int parse_remove(const char *list, int **out, int *count) {
  size_t cap = 2;
  for (const char *c = list; *c; c++) cap += 2 * (*c == ',');
  int *v = malloc(cap * sizeof *v);
  if (!v) return cli_fail("generate", "out of memory");
  *out = v, *count = 0;
  const char *c = list;
  for (;;) {
    char *end;
    long lv = strtol(c, &end, 10), pos;
    if (end == c || *end != ':') break;
    c = end + 1;
    pos = strtol(c, &end, 10);
    if (end == c || lv < 1 || lv > INT_MAX || pos < 1 || pos > 3) break;
    v[2 * *count] = (int)lv, v[2 * *count + 1] = (int)pos, ++*count;
    if (!*end) return 0;
    if (*end != ',') break;
    c = end + 1;
  }
  return cli_fail("generate",
                  "--remove needs LEVEL:POSITION pairs separated by commas (levels from 1, "
                  "positions 1..3), got '%s'",
                  list);
}

/* Kind-specific defaults and checks after parsing (us_gen_settle); 0 or
 * an exit code. */
static int settle(GenFn fn, us_GenSettings *g, const Extra *x) {
  us_GenGiven given = {x->rand_width, x->height_given, x->tries_given, x->returns_given,
                       x->remove != NULL};
  switch (us_gen_settle(fn, g, &given)) {
  case US_GEN_FITS: return 0;
  case US_GEN_REMOVE_NOT_JENGA: return cli_fail("generate", "--remove is for jenga");
  case US_GEN_RETURNS_NOT_WALL3D: return cli_fail("generate", "--returns is for wall3d");
  case US_GEN_BLOCK_WIDTH_FIXED:
    return cli_fail("generate", "%s: block widths are fixed; set the structure width with --width",
                    fn == us_gen_random ? "random" : fn == us_gen_stacker ? "stacker" : "random3d");
  case US_GEN_WIDTH_NOT_RANDOM: break;
  }
  return cli_fail("generate", "--width is for random, stacker and random3d (structure width in "
                              "blocks); use --block-width");
}

const char *cli_generator_kind(int i) {
  const char *kind = us_gen_kind(i);
  return kind ? kind : "unknown";
}

/* "unknown kind 'castle' (column, pyramid, ...)", with the nearest kind. */
static int unknown_kind(const char *kind) {
  char list[256] = "";
  size_t len = 0;
  for (int k = 0; us_gen_kind(k) && len < sizeof list; k++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", us_gen_kind(k));
  const char *near = cli_nearest_word(kind, cli_generator_kind);
  if (near) return cli_fail("generate", "unknown kind '%s' (%s); did you mean '%s'?", kind, list, near);
  return cli_fail("generate", "unknown kind '%s' (%s)", kind, list);
}

/* One structure into `out`; the exit code. */
static int generate_one(GenFn fn, const us_GenSettings *g, const Extra *x, const char *kind,
                        const char *out) {
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = fn(g, &err);
  if (!s && err.code == US_ERR_TIME_LIMIT) { /* an outcome: nothing written */
    printf("stopped: %s (--time-limit %g); nothing written\n", err.msg, x->time_limit);
    return CLI_EXIT_UNDECIDED;
  }
  if (!s || us_structure_write(s, out, &err)) {
    us_structure_free(s);
    return cli_error("generate", &err);
  }
  if (!x->count) printf("wrote %s: %s, %d bodies, %d contacts\n", out, kind, s->nbody, s->ncontact);
  if (!x->count && fn == us_gen_random3d && s->nbody < g->n)
    printf("random3d: %d of %d boxes placed: %d drops in a row were discarded (--max-tries)\n",
           s->nbody, g->n, g->max_tries);
  us_structure_free(s);
  return CLI_EXIT_OK;
}

/* --count N: seeds S .. S+N-1 into DIR/KIND-SEED.json, the seed padded
 * to the last one's width so that names sort as seeds (batch reads a
 * directory sorted); --time-limit bounds the whole run. */
static int generate_many(GenFn fn, us_GenSettings *g, const Extra *x, const char *kind,
                         const char *dir) {
  if (mkdir(dir, 0777) && errno != EEXIST)
    return cli_fail("generate", "%s: cannot create the directory: %s", dir, strerror(errno));
  struct stat st;
  if (stat(dir, &st) || !S_ISDIR(st.st_mode))
    return cli_fail("generate", "--count needs -o DIR/, a directory; %s is not one", dir);
  unsigned long first = g->seed, last = first + (unsigned long)x->count - 1;
  int width = snprintf(NULL, 0, "%lu", last);
  size_t dl = strlen(dir);
  const char *sep = dl && dir[dl - 1] == '/' ? "" : "/";
  for (int k = 0; k < x->count; k++) {
    char path[4096];
    g->seed = first + (unsigned long)k;
    snprintf(path, sizeof path, "%s%s%s-%0*lu.json", dir, sep, kind, width, g->seed);
    int code = generate_one(fn, g, x, kind, path);
    if (code) return code == CLI_EXIT_UNDECIDED ? printf("%d of %d written\n", k, x->count), code : code;
  }
  printf("wrote %d structures to %s: %s-%0*lu.json .. %s-%lu.json\n", x->count, dir, kind, width,
         first, kind, last);
  return CLI_EXIT_OK;
}

int cmd_generate(int argc, char **argv) {
  us_GenSettings g = us_gen_default_settings();
  int default_rows = g.rows;
  g.rows = -1; /* to see whether --rows was given */
  Extra x = {0, NULL, 0, 0, 0, 0, 0};
  const char *out = NULL;
  if (argc < 2) return parse(0, NULL, &g, &x, &out); /* the help on stderr, exit 2 */
  if (cli_is_help(argv[1])) return parse(argc, argv, &g, &x, &out) < 0 ? CLI_EXIT_OK : CLI_EXIT_ERR;
  GenFn fn = us_gen_find(argv[1]);
  if (!fn) return unknown_kind(argv[1]);
  int r = parse(argc - 1, argv + 1, &g, &x, &out);
  if (r) return r < 0 ? CLI_EXIT_OK : r;
  if (!out) return cli_fail("generate", "no output given: use -o FILE");
  if (!x.count && cli_check_output("generate", out, NULL, 0)) return CLI_EXIT_ERR;
  if ((fn == us_gen_pyramid || fn == us_gen_pyramid3d) && g.rows > 0) g.n = g.rows;
  if (g.rows < 0) g.rows = default_rows;
  if (settle(fn, &g, &x)) return CLI_EXIT_ERR;
  int *pairs = NULL;
  if (x.remove && parse_remove(x.remove, &pairs, &g.nremove)) return free(pairs), CLI_EXIT_ERR;
  g.remove = pairs;
  g.deadline = cli_deadline(x.time_limit);
  int code = x.count ? generate_many(fn, &g, &x, argv[1], out) : generate_one(fn, &g, &x, argv[1], out);
  free(pairs);
  return code;
}
