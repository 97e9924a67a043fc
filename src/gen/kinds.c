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
