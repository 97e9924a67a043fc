/* Candidate ordering: which body the graph searches try to move first.
 *
 * "highest" sorts bodies by the top of their geometry (the highest vertex,
 * or the centre for bodies without geometry), then by centre height, then
 * by index, so ties are deterministic. Going down the highest body is
 * removed first; going up the order is reversed (the lowest body is placed
 * first), so both directions mirror the same intuition: a structure comes
 * apart top-down and goes up bottom-up. Only the bodies of the part being
 * planned are candidates. */
#include "order.h"

#include "model/model.h"

#include <stdlib.h>

typedef struct {
  double top, mid;
  int body;
} Key;

static double body_top(const us_Structure *s, const us_Body *b) {
  double lo, hi;
  us_body_vertical_range(s, b, &lo, &hi);
  return hi;
}

/* Descending height, ascending index. */
static int cmp_highest(const void *pa, const void *pb) {
  const Key *a = pa, *b = pb;
  if (a->top != b->top) return a->top > b->top ? -1 : 1;
  if (a->mid != b->mid) return a->mid > b->mid ? -1 : 1;
  return (a->body > b->body) - (a->body < b->body);
}

static void reverse(int *v, int n) {
  for (int i = 0, j = n - 1; i < j; i++, j--) {
    int t = v[i];
    v[i] = v[j];
    v[j] = t;
  }
}

int us_plan_sort_highest(const us_Structure *s, int *bodies, int n) {
  Key *keys = us_malloc((size_t)(n > 0 ? n : 1) * sizeof *keys);
  if (!keys) return -1;
  for (int i = 0; i < n; i++) {
    const us_Body *b = &s->bodies[bodies[i]];
    keys[i].top = body_top(s, b);
    keys[i].mid = b->com[s->dim == 3 ? 2 : 1];
    keys[i].body = bodies[i];
  }
  qsort(keys, (size_t)n, sizeof *keys, cmp_highest);
  for (int i = 0; i < n; i++) bodies[i] = keys[i].body;
  us_free(keys);
  return 0;
}

int us_plan_order_candidates(us_SearchCtx *ctx) {
  ctx->ncand = 0;
  for (int i = 0; i < ctx->s->nbody; i++)
    if (us_bitset_get(&ctx->part, i)) ctx->cand[ctx->ncand++] = i;
  if (ctx->set->order != US_ORDER_INPUT && us_plan_sort_highest(ctx->s, ctx->cand, ctx->ncand))
    return -1;
  int flip = (ctx->set->order == US_ORDER_LOWEST) != (ctx->set->direction == US_DIR_UP);
  if (ctx->set->order == US_ORDER_INPUT) flip = ctx->set->direction == US_DIR_UP;
  if (flip) reverse(ctx->cand, ctx->ncand);
  return 0;
}
