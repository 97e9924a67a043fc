/* unstack generate: write a generated structure (column, pyramid, wall,
 * arch, random, stacker; in 3D tower, pyramid3d, wall3d, dome, jenga,
 * random3d) as a structure file. */
#include "options.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char help[] =
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
    "                                         --max-tries discarded drops in a row (fewer)\n"
    "\n"
    "common options:\n"
    "  -o, --output FILE     structure file to write (required)\n"
    "  --block-width X       block width (default 1; not for random, stacker, random3d)\n"
    "  --block-height Y      block height (default 0.5; jenga 0.6)\n"
    "  --block-depth D       3D block depth along y (tower, pyramid3d; default 1)\n"
    "  --friction MU         Coulomb coefficient written to the file (default 0.5;\n"
    "                        'infinite': no sliding)\n"
    "  --density D           density of every block (default 1)\n"
    "  --max-tries N         random, stacker: attempts before giving up (default 10000);\n"
    "                        random3d: discarded drops in a row before stopping (200)\n"
    "  --time-limit S        stop after S seconds (random3d), nothing written, exit 3\n"
    "\n"
    "exit: 0 written, 2 usage error (nothing written), 3 stopped by --time-limit (nothing\n"
    "written)\n";

typedef us_Structure *(*GenFn)(const us_GenSettings *, us_Error *);

static const struct {
  const char *kind;
  GenFn fn;
} kinds[] = {{"column", us_gen_column}, {"pyramid", us_gen_pyramid}, {"wall", us_gen_wall},
             {"arch", us_gen_arch}, {"random", us_gen_random}, {"stacker", us_gen_stacker},
             {"tower", us_gen_tower}, {"pyramid3d", us_gen_pyramid3d}, {"wall3d", us_gen_wall3d},
             {"dome", us_gen_dome}, {"jenga", us_gen_jenga}, {"random3d", us_gen_random3d}};

/* Integer options and where they go. */
static int int_option(const char *name, us_GenSettings *g, int **dst) {
  *dst = !strcmp(name, "--blocks") || !strcmp(name, "--voussoirs") || !strcmp(name, "--courses") ||
                 !strcmp(name, "--levels")
             ? &g->n
         : !strcmp(name, "--segments") ? &g->segments
         : !strcmp(name, "--rows") ? &g->rows
         : !strcmp(name, "--cols") ? &g->cols
         : !strcmp(name, "--max-tries") ? &g->max_tries
         : !strcmp(name, "--loose") ? &g->loose
                                          : NULL;
  return *dst != NULL;
}

static int real_option(const char *name, us_GenSettings *g, double **dst) {
  *dst = !strcmp(name, "--block-width") ? &g->width
         : !strcmp(name, "--block-height") ? &g->height
         : !strcmp(name, "--radius") ? &g->radius
         : !strcmp(name, "--thickness") ? &g->thickness
         : !strcmp(name, "--friction") ? &g->friction
         : !strcmp(name, "--density") ? &g->density
         : !strcmp(name, "--block-depth") ? &g->depth
         : !strcmp(name, "--jitter") ? &g->jitter
         : !strcmp(name, "--oculus") ? &g->oculus
         : !strcmp(name, "--chamfer") ? &g->chamfer
                                         : NULL;
  return *dst != NULL;
}

/* Options that are not plain settings, and which defaults were overridden. */
typedef struct Extra {
  double rand_width;  /* --width, 0 when not given */
  const char *remove; /* --remove list, NULL when not given */
  int height_given, tries_given;
  int returns_given; /* --returns, for wall3d only */
  double time_limit;  /* --time-limit, 0 when not given */
} Extra;

static int parse_option(int argc, char **argv, int *i, us_GenSettings *g, Extra *x) {
  int *ip;
  double *dp;
  long n;
  const char *name = argv[*i], *v;
  x->height_given |= !strcmp(name, "--block-height");
  x->tries_given |= !strcmp(name, "--max-tries");
  if (!strcmp(name, "--cap")) {
    g->cap = 1;
  } else if (!strcmp(name, "--remove")) {
    if (!(x->remove = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
  } else if (!strcmp(name, "--width")) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (cli_parse_double(v, &x->rand_width) || x->rand_width <= 0)
      return cli_fail("generate", "--width needs a positive number, got '%s'", v);
  } else if (!strcmp(name, "--returns")) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (cli_parse_long(v, &n) || n < 0)
      return cli_fail("generate", "--returns needs a non-negative integer (bricks), got '%s'", v);
    if (n > INT_MAX) return cli_fail("generate", "--returns: %s is too large (at most %d)", v, INT_MAX);
    g->returns = (int)n, x->returns_given = 1;
  } else if (!strcmp(name, "--time-limit")) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (cli_parse_double(v, &x->time_limit) || x->time_limit <= 0)
      return cli_fail("generate", "--time-limit needs a positive number of seconds, got '%s'", v);
  } else if (!strcmp(name, "--seed")) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (cli_parse_long(v, &n) || n < 0)
      return cli_fail("generate", "--seed needs a non-negative integer, got '%s'", v);
    g->seed = (unsigned long)n;
  } else if (int_option(name, g, &ip)) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (cli_parse_long(v, &n) || n < 1)
      return cli_fail("generate", "%s needs a positive integer, got '%s'", name, v);
    if (n > INT_MAX) /* the generator names its own, smaller, limits */
      return cli_fail("generate", "%s: %s is too large (at most %d)", name, v, INT_MAX);
    *ip = (int)n;
  } else if (real_option(name, g, &dp)) {
    if (!(v = cli_value("generate", argc, argv, i))) return CLI_EXIT_ERR;
    if (dp == &g->friction && !strcmp(v, "infinite"))
      *dp = INFINITY; /* no sliding */
    else if (cli_parse_double(v, dp))
      return cli_fail("generate", "%s needs a number, got '%s'", name, v);
  } else {
    return cli_fail("generate", "unknown option '%s'", name);
  }
  return 0;
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

/* Kind-specific defaults and checks after parsing; 0 or an exit code. */
static int settle(GenFn fn, us_GenSettings *g, const Extra *x, double block_width) {
  if (fn == us_gen_jenga && !x->height_given) g->height = 0.6 * g->width; /* the game's pieces */
  if (fn == us_gen_random3d && !x->tries_given) g->max_tries = 200;
  if (x->remove && fn != us_gen_jenga) return cli_fail("generate", "--remove is for jenga");
  if (x->returns_given && fn != us_gen_wall3d) return cli_fail("generate", "--returns is for wall3d");
  if (fn == us_gen_random || fn == us_gen_stacker || fn == us_gen_random3d) {
    const char *kind = fn == us_gen_random ? "random" : fn == us_gen_stacker ? "stacker" : "random3d";
    if (g->width != block_width)
      return cli_fail("generate", "%s: block widths are fixed; set the structure width with --width",
                      kind);
    g->width = x->rand_width > 0 ? x->rand_width
               : fn == us_gen_random ? 5.0
               : fn == us_gen_stacker ? 12.0
                                       : 4.0;
  } else if (x->rand_width > 0) {
    return cli_fail("generate", "--width is for random, stacker and random3d (structure width in "
                                "blocks); use --block-width");
  }
  return 0;
}

int cmd_generate(int argc, char **argv) {
  if (argc < 2 || cli_is_help(argv[1])) {
    fputs(help, argc < 2 ? stderr : stdout);
    return argc < 2 ? CLI_EXIT_ERR : CLI_EXIT_OK;
  }
  GenFn fn = NULL;
  for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
    if (!strcmp(argv[1], kinds[k].kind)) fn = kinds[k].fn;
  if (!fn)
    return cli_fail("generate",
                    "unknown kind '%s' (column, pyramid, wall, arch, random, stacker, tower, "
                    "pyramid3d, wall3d, dome, jenga, random3d)",
                    argv[1]);
  us_GenSettings g = us_gen_default_settings();
  int default_rows = g.rows;
  g.rows = -1; /* to see whether --rows was given */
  double block_width = g.width;
  Extra x = {0, NULL, 0, 0, 0, 0};
  const char *out = NULL;
  for (int i = 2; i < argc; i++) {
    if (cli_is_help(argv[i])) return fputs(help, stdout), CLI_EXIT_OK;
    if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
      if (!(out = cli_value("generate", argc, argv, &i))) return CLI_EXIT_ERR;
    } else if (parse_option(argc, argv, &i, &g, &x)) {
      return CLI_EXIT_ERR;
    }
  }
  if (!out) return cli_fail("generate", "no output given: use -o FILE");
  if (cli_check_output("generate", out, NULL, 0)) return CLI_EXIT_ERR;
  if ((fn == us_gen_pyramid || fn == us_gen_pyramid3d) && g.rows > 0) g.n = g.rows;
  if (g.rows < 0) g.rows = default_rows;
  if (settle(fn, &g, &x, block_width)) return CLI_EXIT_ERR;
  int *pairs = NULL;
  if (x.remove && parse_remove(x.remove, &pairs, &g.nremove)) return free(pairs), CLI_EXIT_ERR;
  g.remove = pairs;
  us_Error err;
  us_error_clear(&err);
  g.deadline = cli_deadline(x.time_limit);
  us_Structure *s = fn(&g, &err);
  free(pairs);
  if (!s && err.code == US_ERR_TIME_LIMIT) { /* an outcome: nothing written */
    printf("stopped: %s (--time-limit %g); nothing written\n", err.msg, x.time_limit);
    return CLI_EXIT_UNDECIDED;
  }
  if (!s || us_structure_write(s, out, &err)) {
    us_structure_free(s);
    return cli_error("generate", &err);
  }
  printf("wrote %s: %s, %d bodies, %d contacts\n", out, argv[1], s->nbody, s->ncontact);
  if (fn == us_gen_random3d && s->nbody < g.n)
    printf("random3d: %d of %d boxes placed: %d drops in a row were discarded (--max-tries)\n",
           s->nbody, g.n, g.max_tries);
  us_structure_free(s);
  return CLI_EXIT_OK;
}
