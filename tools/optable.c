/* The option-table engine (optable.h): parses a command line by its table,
 * prints the table as the options part of --help, and finds the nearest
 * word for "did you mean". */
#include "optable.h"

#include "cli.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define HELP_COL 24   /* help texts start in this column */
#define HELP_WIDTH 80 /* and are wrapped before this one */

/* ------------------------------------------------------------ nearest */

/* Edit distance with adjacent transpositions (optimal string alignment),
 * capped: words longer than 63 characters are never near. */
static int distance(const char *a, const char *b) {
  size_t n = strlen(a), m = strlen(b);
  if (n > 63 || m > 63) return INT_MAX;
  int d[64][64];
  for (size_t i = 0; i <= n; i++) d[i][0] = (int)i;
  for (size_t j = 0; j <= m; j++) d[0][j] = (int)j;
  for (size_t i = 1; i <= n; i++)
    for (size_t j = 1; j <= m; j++) {
      int cost = a[i - 1] != b[j - 1];
      int v = d[i - 1][j - 1] + cost;
      if (d[i - 1][j] + 1 < v) v = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < v) v = d[i][j - 1] + 1;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < v)
        v = d[i - 2][j - 2] + 1;
      d[i][j] = v;
    }
  return d[n][m];
}

const char *cli_nearest(const char *word, const char *const *cands, int n) {
  int len = (int)strlen(word), best = INT_MAX, limit = len / 3;
  if (limit < 1) limit = 1;
  if (limit > 3) limit = 3;
  const char *pick = NULL;
  for (int k = 0; k < n; k++) {
    if (!cands[k]) continue;
    int d = distance(word, cands[k]);
    if (d < best) best = d, pick = cands[k];
  }
  return best <= limit ? pick : NULL;
}

const char *cli_nearest_word(const char *word, CliWordFn fn) {
  const char *cands[32];
  int n = 0;
  while (n < 32 && strcmp(fn(n), "unknown")) cands[n] = fn(n), n++;
  return cli_nearest(word, cands, n);
}

/* ------------------------------------------------------------ parsing */

static const CliOpt *find(const CliOpt *o, const char *arg) {
  for (; o->name; o++)
    if (!strcmp(arg, o->name) || (o->alias && !strcmp(arg, o->alias))) return o;
  return NULL;
}

static int unknown_option(const CliSpec *sp, const char *arg) {
  char name[64];
  size_t len = strcspn(arg, "=");
  snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1), arg);
  const char *cands[128];
  int n = 0;
  for (const CliOpt *o = sp->opts; o->name && n < 126; o++) {
    cands[n++] = o->name;
    if (o->alias) cands[n++] = o->alias;
  }
  const char *near = cli_nearest(name, cands, n);
  if (near) return cli_fail(sp->cmd, "unknown option '%s' (did you mean %s?)", arg, near);
  return cli_fail(sp->cmd, "unknown option '%s'", arg);
}

/* "unknown WHAT 'VALUE' (w0, w1, ...)", and the nearest word when near. */
static int unknown_word(const char *cmd, const CliOpt *o, const char *v) {
  char list[256] = "";
  size_t len = 0;
  for (int i = 0; i < 32 && strcmp(o->word(i), "unknown") && len < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", o->word(i));
  const char *near = cli_nearest_word(v, o->word);
  if (near) return cli_fail(cmd, "unknown %s '%s' (%s); did you mean '%s'?", o->what, v, list, near);
  return cli_fail(cmd, "unknown %s '%s' (%s)", o->what, v, list);
}

static int bad_value(const char *cmd, const CliOpt *o, const char *v, const char *dflt) {
  return cli_fail(cmd, "%s needs %s, got '%s'", o->name, o->need ? o->need : dflt, v);
}

/* An integer option into a long: range from the table, then the type's. */
static int integer(const char *cmd, const CliOpt *o, const char *v, long max, long *out) {
  const char *dflt = !o->ranged ? "an integer"
                     : o->lo >= 1 ? "a positive integer"
                     : o->lo >= 0 ? "a non-negative integer"
                                  : "an integer";
  if (cli_parse_long(v, out)) return bad_value(cmd, o, v, dflt);
  if (o->ranged && ((double)*out < o->lo || (o->hi > 0 && (double)*out > o->hi)))
    return bad_value(cmd, o, v, dflt);
  if (*out > max) return cli_fail(cmd, "%s: %s is too large (at most %ld)", o->name, v, max);
  if (*out < -max) return bad_value(cmd, o, v, dflt);
  return 0;
}

static int real(const char *cmd, const CliOpt *o, const char *v, double *out) {
  if (o->inf_ok && !strcmp(v, "infinite")) return *out = INFINITY, 0;
  double x;
  if (cli_parse_double(v, &x) ||
      (o->ranged && (x < o->lo || (o->open && x == o->lo) || (o->hi > 0 && x > o->hi))))
    return bad_value(cmd, o, v, "a number");
  *out = x;
  return 0;
}

/* Is w one of the '|'-separated words of list? */
static int is_word_of(const char *w, const char *list) {
  size_t n = strlen(w);
  for (const char *p = list; *p;) {
    const char *bar = strchr(p, '|');
    size_t len = bar ? (size_t)(bar - p) : strlen(p);
    if (len == n && !strncmp(p, w, n)) return 1;
    p += len + (bar != NULL);
  }
  return 0;
}

/* Apply option o found at argv[*i], with its value after '=' in `eq` (NULL:
 * none, the value is the next argument); 0, or CLI_EXIT_ERR (message
 * printed). */
static int apply(const char *cmd, const CliOpt *o, const char *eq, int argc, char **argv, int *i) {
  const char *v = eq;
  long n;
  int no_value = o->kind == CLI_K_FLAG || (o->kind == CLI_K_CALL && !o->takes_value);
  if (eq && no_value && !o->optional) return cli_fail(cmd, "option %s takes no value", o->name);
  if (o->given) *o->given = 1;
  if (o->kind == CLI_K_FLAG) return *(int *)o->dst = o->flag, 0;
  if (no_value && !eq && o->next_words && *i + 1 < argc && is_word_of(argv[*i + 1], o->next_words))
    v = argv[++*i];
  if (no_value) return o->set(v, o->dst, cmd) ? CLI_EXIT_ERR : 0;
  if (!v && !(v = cli_value(cmd, argc, argv, i))) return CLI_EXIT_ERR;
  switch (o->kind) {
  case CLI_K_INT:
    if (integer(cmd, o, v, INT_MAX, &n)) return CLI_EXIT_ERR;
    return *(int *)o->dst = (int)n, 0;
  case CLI_K_LONG: return integer(cmd, o, v, LONG_MAX, (long *)o->dst) ? CLI_EXIT_ERR : 0;
  case CLI_K_ULONG:
    if (integer(cmd, o, v, LONG_MAX, &n)) return CLI_EXIT_ERR;
    return *(unsigned long *)o->dst = (unsigned long)n, 0;
  case CLI_K_REAL: return real(cmd, o, v, (double *)o->dst) ? CLI_EXIT_ERR : 0;
  case CLI_K_TEXT: return *(const char **)o->dst = v, 0;
  case CLI_K_ENUM: return o->parse(v, o->dst) ? unknown_word(cmd, o, v) : 0;
  case CLI_K_CALL: return o->set(v, o->dst, cmd) ? CLI_EXIT_ERR : 0;
  default: return cli_fail(cmd, "option %s: bad table entry", o->name);
  }
}

/* "--name=value": the option named before '=' and the value after it. */
static const CliOpt *find_with_value(const CliOpt *opts, const char *a, const char **eq) {
  char name[64];
  const char *e = a[0] == '-' && a[1] == '-' ? strchr(a, '=') : NULL;
  *eq = NULL;
  if (!e || (size_t)(e - a) >= sizeof name) return find(opts, a);
  memcpy(name, a, (size_t)(e - a));
  name[e - a] = 0;
  const CliOpt *o = find(opts, name);
  if (o) *eq = e + 1;
  return o;
}

int cli_parse(const CliSpec *sp, int argc, char **argv) {
  int npos = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *eq;
    const CliOpt *o;
    if (cli_is_help(a)) return cli_print_help(sp, stdout), -1;
    if ((o = find_with_value(sp->opts, a, &eq))) {
      if (apply(sp->cmd, o, eq, argc, argv, &i)) return CLI_EXIT_ERR;
    } else if (a[0] == '-' && a[1]) {
      return unknown_option(sp, a);
    } else if (npos == sp->maxpos) {
      return sp->too_many ? cli_fail(sp->cmd, "%s", sp->too_many)
                          : cli_fail(sp->cmd, "unknown option '%s'", a);
    } else {
      sp->pos[npos++] = a;
    }
  }
  return 0;
}

/* ------------------------------------------------------------ help */

/* Text from column `col`, words wrapped before HELP_WIDTH; '\n' breaks. */
static void put_wrapped(FILE *f, const char *t, int col) {
  int x = col;
  while (*t) {
    if (*t == '\n') {
      fprintf(f, "\n%*s", col, "");
      x = col, t++;
      continue;
    }
    size_t w = strcspn(t, " \n");
    if (x > col && x + 1 + (int)w > HELP_WIDTH) fprintf(f, "\n%*s", col, ""), x = col;
    else if (x > col) fputc(' ', f), x++;
    fprintf(f, "%.*s", (int)w, t);
    x += (int)w, t += w;
    while (*t == ' ') t++;
  }
  fputc('\n', f);
}

void cli_print_help(const CliSpec *sp, FILE *f) {
  fputs(sp->head, f);
  fputs("\noptions:\n", f);
  for (const CliOpt *o = sp->opts; o->name; o++) {
    char left[96];
    int n = snprintf(left, sizeof left, "  %s%s%s%s%s", o->alias ? o->alias : "",
                     o->alias ? ", " : "", o->name, o->value ? " " : "", o->value ? o->value : "");
    if (n >= HELP_COL) fprintf(f, "%s\n%*s", left, HELP_COL, "");
    else fprintf(f, "%-*s", HELP_COL, left);
    put_wrapped(f, o->help, HELP_COL);
  }
  if (sp->tail) fprintf(f, "\n%s", sp->tail);
}
