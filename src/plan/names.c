/* The planner's enum names: one table per enum, used by the plan files
 * (src/io) and the command-line tool, so a word is spelled in one place. */
#include "core/core.h"

#include <string.h>

static const char *const status_names[] = {"found", "none", "unstable", "limit", "undecided"};
static const char *const search_names[] = {"assemble", "dfs", "bfs", "random"};
static const char *const order_names[] = {"highest", "lowest", "input"};
static const char *const direction_names[] = {"down", "up"};
static const char *const removal_names[] = {"any", "up", "free"};
static const char *const action_names[] = {"place", "grab", "release"};
static const char *const rule_names[] = {"memo", "ground", "union", "components", "greedy"};

static const char *name_of(const char *const *t, int n, int v) {
  return v >= 0 && v < n ? t[v] : "unknown";
}

static int parse_in(const char *const *t, int n, const char *w, int *out) {
  for (int i = 0; w && i < n; i++)
    if (!strcmp(w, t[i])) return *out = i, 0;
  return -1;
}

#define US_NAMES(fn, T, table, n)                                              \
  const char *us_##fn##_name(T v) { return name_of(table, n, (int)v); }        \
  int us_##fn##_parse(const char *w, T *out) {                                 \
    int i;                                                                     \
    if (parse_in(table, n, w, &i)) return -1;                                  \
    *out = (T)i;                                                               \
    return 0;                                                                  \
  }

US_NAMES(plan_status, us_PlanStatus, status_names, 5)
US_NAMES(search, us_Search, search_names, 4)
US_NAMES(order, us_Order, order_names, 3)
US_NAMES(direction, us_Direction, direction_names, 2)
US_NAMES(removal, us_Removal, removal_names, 3)
US_NAMES(action, us_ActionVerb, action_names, 3)

const char *us_rule_name(int bit) {
  for (int i = 0; i < 5; i++)
    if (bit == 1 << i) return rule_names[i];
  return "unknown";
}

int us_rules_parse(const char *list, unsigned *out) {
  if (!strcmp(list, "all")) return *out = US_RULE_ALL, 0;
  if (!strcmp(list, "none")) return *out = 0, 0;
  unsigned rules = 0;
  for (const char *p = list; *p;) {
    size_t len = strcspn(p, ",");
    int found = -1;
    for (int i = 0; i < 5 && found < 0; i++)
      if (strlen(rule_names[i]) == len && !strncmp(p, rule_names[i], len)) found = i;
    if (found < 0) return -1;
    rules |= 1u << found;
    p += len + (p[len] == ',');
  }
  *out = rules;
  return 0;
}
