/* The generators by name: the table `unstack generate` and the bindings
 * look kinds up in (nothing in the generators calls it). */
#include "gen.h"

#include <string.h>

/* Every generator, in the order `unstack generate --help` lists them. */
static const struct {
  const char *kind;
  us_GenFn fn;
} gen_kinds[] = {{"column", us_gen_column},       {"pyramid", us_gen_pyramid},
                 {"wall", us_gen_wall},           {"arch", us_gen_arch},
                 {"random", us_gen_random},       {"stacker", us_gen_stacker},
                 {"tower", us_gen_tower},         {"pyramid3d", us_gen_pyramid3d},
                 {"wall3d", us_gen_wall3d},       {"dome", us_gen_dome},
                 {"jenga", us_gen_jenga},         {"random3d", us_gen_random3d}};
#define GEN_KINDS ((int)(sizeof gen_kinds / sizeof gen_kinds[0]))

us_GenFn us_gen_find(const char *kind) {
  for (int k = 0; kind && k < GEN_KINDS; k++)
    if (!strcmp(kind, gen_kinds[k].kind)) return gen_kinds[k].fn;
  return NULL;
}

const char *us_gen_kind(int k) { return k >= 0 && k < GEN_KINDS ? gen_kinds[k].kind : NULL; }

us_GenMisfit us_gen_settle(us_GenFn fn, us_GenSettings *g, const us_GenGiven *given) {
  int random = fn == us_gen_random || fn == us_gen_stacker || fn == us_gen_random3d;
  if (fn == us_gen_jenga && !given->height) g->height = 0.6 * g->width; /* the game's pieces */
  if (fn == us_gen_random3d && !given->tries) g->max_tries = 200;
  if (given->remove && fn != us_gen_jenga) return US_GEN_REMOVE_NOT_JENGA;
  if (given->returns && fn != us_gen_wall3d) return US_GEN_RETURNS_NOT_WALL3D;
  if (!random) return given->width > 0 ? US_GEN_WIDTH_NOT_RANDOM : US_GEN_FITS;
  if (g->width != us_gen_default_settings().width) return US_GEN_BLOCK_WIDTH_FIXED;
  g->width = given->width > 0          ? given->width
             : fn == us_gen_random  ? 5.0
             : fn == us_gen_stacker ? 12.0
                                    : 4.0;
  return US_GEN_FITS;
}
