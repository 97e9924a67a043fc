/* Tests of the sub-graph count (src/analysis/count*.c) and its big
 * integers (src/analysis/bigint.c).
 *
 * The reference is an independent brute force: every subset of the
 * movable bodies, flooded from the ground through s->contacts directly
 * (fixed bodies merged into the ground here, not by count.c's graph).
 * Closed forms: a column of n blocks has n + 1 (a path), k loose blocks
 * 2^k (a star), a cycle through the ground of k bodies k (k + 1) / 2 + 1,
 * the complete graph on k bodies all touching the ground 2^k. Big-integer
 * constants were computed with Python's integers. */
#include "test.h"
#include "scenes.h"

#include "analysis/bigint.h"

/* ---------------------------------------------------------------- scenes */

/* Rows of boxes 1 x 0.5 from half-block indices, as src/gen/regular.c
 * lays them out (the test links us_analysis only, not the generators). */
static int row_box(us_Structure *s, int *k, int row, int q0, int q1) {
  char id[16];
  snprintf(id, sizeof id, "b%d", ++*k);
  double xy[8] = {0.5 * q0, 0.5 * row, 0.5 * q1, 0.5 * row,
                  0.5 * q1, 0.5 * (row + 1), 0.5 * q0, 0.5 * (row + 1)};
  return scene_polygon(s, id, 4, xy, 0) < 0
             ? -1
             : 0;
}

static us_Structure *column(int n) {
  us_Structure *s = us_structure_new(2);
  int k = 0;
  for (int r = 0; r < n; r++) row_box(s, &k, r, 0, 2);
  return scene_seal(s);
}

/* k blocks on the ground, one block apart: no two touch. */
static us_Structure *loose(int n) {
  us_Structure *s = us_structure_new(2);
  int k = 0;
  for (int j = 0; j < n; j++) row_box(s, &k, 0, 4 * j, 4 * j + 2);
  return scene_seal(s);
}

/* Stack-bond pyramid: row r holds rows - r blocks, shifted half a block. */
static us_Structure *pyramid(int rows) {
  us_Structure *s = us_structure_new(2);
  int k = 0;
  for (int r = 0; r < rows; r++)
    for (int j = 0; j < rows - r; j++) row_box(s, &k, r, r + 2 * j, r + 2 * j + 2);
  return scene_seal(s);
}

/* Running-bond wall: even rows `cols` bricks, odd rows half bricks at
 * both ends. */
static us_Structure *wall(int rows, int cols) {
  us_Structure *s = us_structure_new(2);
  int k = 0;
  for (int r = 0; r < rows; r++) {
    if (r % 2 == 0) {
      for (int j = 0; j < cols; j++) row_box(s, &k, r, 2 * j, 2 * j + 2);
      continue;
    }
    row_box(s, &k, r, 0, 1);
    for (int j = 0; j < cols - 1; j++) row_box(s, &k, r, 2 * j + 1, 2 * j + 3);
    row_box(s, &k, r, 2 * cols - 1, 2 * cols);
  }
  return scene_seal(s);
}

/* Point bodies with explicit contacts: any graph. edges[2 i], edges[2 i +
 * 1] for i < ne, -1 is the ground; fixed[v] (may be NULL) marks supports. */
static us_Structure *graph(int n, const int *edges, int ne, const int *fixed) {
  us_Structure *s = us_structure_new(2);
  us_Error err;
  for (int v = 0; v < n; v++) {
    char id[16];
    double c[2] = {(double)v, 1.0 + v};
    snprintf(id, sizeof id, "p%d", v);
    us_structure_add_point_body(s, id, 1.0, c, fixed ? fixed[v] : 0, &err);
  }
  double p[3] = {0, 0, 0}, nrm[3] = {0, 1, 0};
  for (int i = 0; i < ne; i++) { /* the ground can only be side a */
    int a = edges[2 * i], b = edges[2 * i + 1];
    if (us_structure_add_contact(s, b < a ? b : a, b < a ? a : b, p, nrm, -1, &err) < 0)
      fprintf(stderr, "graph: %s\n", err.msg);
  }
  return scene_seal(s);
}

/* ----------------------------------------------------------- references */

static int grounded(const us_Structure *s, int b) { return b == US_GROUND || s->bodies[b].fixed; }

/* Brute force: subsets of the movable bodies (at most 24) whose bodies
 * all reach the ground through contacts between bodies of the subset. */
static uint64_t brute(const us_Structure *s) {
  int m = 0, bit[64];
  if (s->nbody > 64) return 0;
  for (int b = 0; b < s->nbody; b++) bit[b] = s->bodies[b].fixed ? -1 : m++;
  if (m > 24) return 0;
  uint32_t adj[32] = {0}, touch = 0;
  for (int k = 0; k < s->ncontact; k++) {
    int a = s->contacts[k].a, b = s->contacts[k].b;
    if (grounded(s, a) && !grounded(s, b)) touch |= 1u << bit[b];
    else if (grounded(s, b) && !grounded(s, a)) touch |= 1u << bit[a];
    else if (!grounded(s, a) && !grounded(s, b))
      adj[bit[a]] |= 1u << bit[b], adj[bit[b]] |= 1u << bit[a];
  }
  uint64_t count = 0;
  for (uint32_t S = 0; S < (1u << m); S++) {
    uint32_t r = S & touch, prev = 0;
    while (r != prev) {
      prev = r;
      for (int v = 0; v < m; v++)
        if (r >> v & 1) r |= adj[v] & S;
    }
    count += r == S;
  }
  return count;
}

/* Count with one method; the value (owned by the caller) or NULL. */
static char *count_value(const us_Structure *s, us_CountMethod m, us_Count *c) {
  us_CountSettings set = us_count_default_settings();
  set.method = m;
  us_Error err;
  if (us_count_subgraphs(s, &set, c, &err) != US_OK) {
    fprintf(stderr, "  count (%s): %s\n", us_count_method_name(m), err.msg);
    return NULL;
  }
  return c->value;
}

/* Every applicable method gives `want` (the tree formula on trees only).
 * 0 or -1 (printed). */
static int all_methods(const us_Structure *s, const char *want) {
  us_CountMethod ms[] = {US_COUNT_AUTO, US_COUNT_FRONTIER, US_COUNT_CONTRACT, US_COUNT_TREE};
  int tree = 0;
  for (int i = 0; i < 4 - !tree; i++) {
    us_Count c;
    char *v = count_value(s, ms[i], &c);
    tree |= c.is_tree;
    int bad = !v || strcmp(v, want);
    if (bad) fprintf(stderr, "  %s: got %s, want %s\n", us_count_method_name(ms[i]), v ? v : "(none)", want);
    us_count_free(&c);
    if (bad) return -1;
  }
  return 0;
}

static int against_brute(const us_Structure *s) {
  char want[32];
  snprintf(want, sizeof want, "%llu", (unsigned long long)brute(s));
  return all_methods(s, want);
}

/* ---------------------------------------------------------------- bigint */

static int big_is(const us_Big *a, const char *want) {
  char *d = us_big_to_dec(a);
  int ok = d && !strcmp(d, want);
  if (!ok) fprintf(stderr, "  big: got %s, want %s\n", d ? d : "(oom)", want);
  us_free(d);
  return ok;
}

static void bigint_known_values(void) {
  us_Big a, b, c;
  us_big_init(&a), us_big_init(&b), us_big_init(&c);
  CHECK(big_is(&a, "0"));
  CHECK(!us_big_set_u64(&a, 1));
  for (int i = 0; i < 200; i++) CHECK(!us_big_mul_u64(&a, 2));
  CHECK(big_is(&a, "1606938044258990275541962092341162602522202993782792835301376"));
  CHECK(!us_big_add(&a, &a)); /* aliased: 2^201 */
  CHECK(big_is(&a, "3213876088517980551083924184682325205044405987565585670602752"));
  CHECK(!us_big_set_u64(&b, UINT64_MAX));
  CHECK(!us_big_add_u64(&b, 1)); /* carry into a new limb */
  CHECK(big_is(&b, "18446744073709551616"));
  uint64_t ones[2] = {UINT64_MAX, UINT64_MAX};
  CHECK(!us_big_set_words(&b, ones, 2));
  CHECK(!us_big_add_u64(&b, 1)); /* the carry runs through every limb */
  CHECK(big_is(&b, "340282366920938463463374607431768211456"));
  CHECK(!us_big_set_u64(&b, UINT64_MAX));
  CHECK(!us_big_mul(&b, &b, &b)); /* aliased square */
  CHECK(big_is(&b, "340282366920938463426481119284349108225"));
  CHECK(!us_big_set_u64(&c, 1));
  for (uint64_t k = 2; k <= 30; k++) CHECK(!us_big_mul_u64(&c, k));
  CHECK(big_is(&c, "265252859812191058636308480000000"));
  CHECK(!us_big_set_u64(&c, 10000000000000000000ull)); /* zero chunks inside */
  CHECK(big_is(&c, "10000000000000000000"));
  us_big_free(&a), us_big_free(&b), us_big_free(&c);
}

static void bigint_products_and_order(void) {
  us_Big a, b, c;
  us_big_init(&a), us_big_init(&b), us_big_init(&c);
  uint64_t p[3] = {1, 0, 1}, q[2] = {UINT64_MAX, UINT64_MAX}; /* 2^128 + 1, 2^128 - 1 */
  CHECK(!us_big_set_words(&a, p, 3) && !us_big_set_words(&b, q, 2));
  CHECK(!us_big_mul(&c, &a, &b));
  CHECK(big_is(&c, "115792089237316195423570985008687907853269984665640564039457584007913129639935"));
  CHECK_INT(us_big_cmp(&a, &b), ==, 1);
  CHECK_INT(us_big_cmp(&b, &a), ==, -1);
  CHECK_INT(us_big_cmp(&c, &c), ==, 0);
  uint64_t v;
  CHECK(!us_big_to_u64(&a, &v));
  us_Big z;
  us_big_init(&z);
  CHECK(!us_big_mul(&c, &c, &z)); /* times zero */
  CHECK(big_is(&c, "0"));
  uint64_t lead0[3] = {7, 0, 0};
  CHECK(!us_big_set_words(&a, lead0, 3));
  CHECK_INT(a.n, ==, 1);
  CHECK(us_big_to_u64(&a, &v) && v == 7);
  us_big_free(&a), us_big_free(&b), us_big_free(&c);
}

/* ---------------------------------------------------------- closed forms */

static void column_is_a_path(void) {
  for (int n = 1; n <= 8; n++) {
    us_Structure *s = column(n);
    CHECK(s);
    char want[16];
    snprintf(want, sizeof want, "%d", n + 1);
    int rc = all_methods(s, want);
    us_Count c;
    us_count_subgraphs(s, NULL, &c, NULL);
    int shape = c.is_tree && c.nedge == n && c.nbody == n && c.method == US_COUNT_TREE;
    us_count_free(&c);
    us_structure_free(s);
    CHECK_INT(rc, ==, 0);
    CHECK(shape);
  }
}

static void column_of_1000(void) {
  us_Structure *s = column(1000);
  CHECK(s);
  us_Count c;
  us_Status st = us_count_subgraphs(s, NULL, &c, NULL);
  int ok = st == US_OK && c.value && !strcmp(c.value, "1001") && c.is_tree;
  us_count_free(&c);
  /* the frontier is 1 wide along the column: the same in linear time */
  char *v = count_value(s, US_COUNT_FRONTIER, &c);
  ok = ok && v && !strcmp(v, "1001") && c.width == 1;
  us_count_free(&c);
  us_structure_free(s);
  CHECK(ok);
}

static void loose_blocks_are_a_star(void) {
  for (int k = 1; k <= 10; k++) {
    us_Structure *s = loose(k);
    CHECK(s);
    char want[16];
    snprintf(want, sizeof want, "%d", 1 << k);
    int rc = all_methods(s, want);
    us_structure_free(s);
    CHECK_INT(rc, ==, 0);
  }
}

static void seventy_loose_blocks_pass_64_bits(void) {
  us_Structure *s = loose(70);
  CHECK(s);
  int rc = all_methods(s, "1180591620717411303424"); /* 2^70 */
  us_structure_free(s);
  CHECK_INT(rc, ==, 0);
}

static void cycle_through_the_ground(void) {
  /* G - p0 - p1 - p2 - p3 - p4 - G */
  int e[] = {-1, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, -1};
  us_Structure *s = graph(5, e, 6, NULL);
  CHECK(s);
  int rc = all_methods(s, "16"); /* 5 * 6 / 2 + 1 */
  int rb = against_brute(s);
  us_structure_free(s);
  CHECK_INT(rc, ==, 0);
  CHECK_INT(rb, ==, 0);
}

static void complete_graph_on_the_ground(void) {
  int e[2 * 21], ne = 0;
  for (int a = 0; a < 6; a++) {
    e[2 * ne] = -1, e[2 * ne + 1] = a, ne++;
    for (int b = a + 1; b < 6; b++) e[2 * ne] = a, e[2 * ne + 1] = b, ne++;
  }
  us_Structure *s = graph(6, e, ne, NULL);
  CHECK(s);
  int rc = all_methods(s, "64");
  us_structure_free(s);
  CHECK_INT(rc, ==, 0);
}

/* A lintel T from a movable block L to a fixed pier, and V on T: the
 * pier merges into the ground, so G-L-T is a triangle: {}, L, T, LT, TV,
 * LTV. */
static void fixed_pier_is_ground(void) {
  us_Structure *s = us_structure_new(2);
  double pier[8] = {2, 0, 3, 0, 3, 1, 2, 1};
  CHECK(scene_box(s, "L", 0, 0, 1, 1, 1) >= 0);
  CHECK(scene_polygon(s, "P", 4, pier, 1) >= 0);
  CHECK(scene_box(s, "T", 0.5, 1, 2, 0.5, 1) >= 0);
  CHECK(scene_box(s, "V", 1, 1.5, 1, 0.5, 1) >= 0);
  CHECK((s = scene_seal(s)));
  int rc = all_methods(s, "6"), rb = against_brute(s);
  us_Count c;
  us_count_subgraphs(s, NULL, &c, NULL);
  int shape = c.nbody == 3 && c.nedge == 4 && !c.is_tree;
  us_count_free(&c);
  us_structure_free(s);
  CHECK_INT(rc, ==, 0);
  CHECK_INT(rb, ==, 0);
  CHECK(shape);
}

/* Bodies outside the ground's component count for nothing. */
static void floating_part_adds_nothing(void) {
  int e[] = {-1, 0, 0, 1, 2, 3, 3, 4, 4, 2, 2, 3}; /* a path, a floating triangle, a repeat */
  us_Structure *s = graph(5, e, 6, NULL);
  CHECK(s);
  us_Count c;
  CHECK_OK(us_count_subgraphs(s, NULL, &c, NULL), &(us_Error){0});
  int ok = c.value && !strcmp(c.value, "3") && c.nbody == 5 && c.nconnected == 2 && c.is_tree &&
           c.nedge == 5;
  us_count_free(&c);
  int rb = against_brute(s);
  us_structure_free(s);
  CHECK(ok);
  CHECK_INT(rb, ==, 0);
}

/* Two paths of 6 bodies from the ground, their bodies alternating in index
 * and position so every candidate order interleaves them unless it sweeps
 * part by part: the frontier stays 1 wide, the count is 7 * 7. */
static void parts_are_swept_apart(void) {
  int e[2 * 12], ne = 0;
  for (int p = 0; p < 2; p++)
    for (int i = 0; i < 6; i++) e[2 * ne] = i ? 2 * (i - 1) + p : -1, e[2 * ne + 1] = 2 * i + p, ne++;
  us_Structure *s = graph(12, e, ne, NULL);
  CHECK(s);
  us_Count c;
  char *v = count_value(s, US_COUNT_FRONTIER, &c);
  int ok = v && !strcmp(v, "49"), width = c.width;
  us_count_free(&c);
  us_structure_free(s);
  CHECK(ok);
  CHECK_INT(width, ==, 1);
}

/* ------------------------------------------------------ against brute force */

static void pyramids_against_brute_force(void) {
  for (int rows = 1; rows <= 5; rows++) {
    us_Structure *s = pyramid(rows);
    CHECK(s);
    int rb = against_brute(s);
    us_structure_free(s);
    CHECK_INT(rb, ==, 0);
  }
}

static void walls_against_brute_force(void) {
  int sizes[][2] = {{1, 3}, {2, 2}, {3, 3}, {4, 3}, {3, 5}, {4, 4}};
  for (int i = 0; i < 6; i++) {
    us_Structure *s = wall(sizes[i][0], sizes[i][1]);
    CHECK(s);
    int rb = against_brute(s);
    us_structure_free(s);
    CHECK_INT(rb, ==, 0);
  }
}

/* The brute-force values of the generator-shaped scenes, pinned: the CLI
 * test (tests/cli/count.sh) expects them from `unstack generate` files. */
static void generator_scenes_pinned(void) {
  us_Structure *sc[4] = {pyramid(3), pyramid(4), wall(3, 3), wall(4, 4)};
  uint64_t want[4] = {46, 596, 554, 88841}, got[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; i++) {
    if (sc[i]) got[i] = brute(sc[i]);
    us_structure_free(sc[i]);
  }
  for (int i = 0; i < 4; i++) CHECK_INT(got[i], ==, want[i]);
}

/* A random graph: n point bodies, edges with probability p, each body on
 * the ground with probability pg, some fixed, some contacts repeated. */
static us_Structure *random_graph(unsigned long long *rng, int n) {
  int e[2 * 200], ne = 0, fixed[16];
  double p = 0.1 + 0.5 * test_rnd(rng), pg = 0.1 + 0.4 * test_rnd(rng);
  for (int v = 0; v < n; v++) fixed[v] = test_rnd(rng) < 0.1;
  for (int a = 0; a < n; a++) {
    if (test_rnd(rng) < pg) e[2 * ne] = -1, e[2 * ne + 1] = a, ne++;
    for (int b = a + 1; b < n; b++)
      for (int rep = test_rnd(rng) < 0.2 ? 2 : 1; rep > 0 && test_rnd(rng) < p; rep--)
        e[2 * ne] = a, e[2 * ne + 1] = b, ne++;
  }
  if (ne == 0) e[0] = -1, e[1] = 0, ne = 1; /* contacts must be explicit */
  return graph(n, e, ne, fixed);
}

static void random_graphs_against_brute_force(void) {
  unsigned long long rng = 0x5eed1234abcdull;
  int trees = 0;
  for (int trial = 0; trial < 300; trial++) {
    us_Structure *s = random_graph(&rng, 1 + trial % 14);
    CHECK(s);
    us_Count c;
    us_count_subgraphs(s, NULL, &c, NULL);
    trees += c.is_tree && c.nconnected > 1;
    us_count_free(&c);
    int rb = against_brute(s);
    if (rb) fprintf(stderr, "  trial %d\n", trial);
    us_structure_free(s);
    CHECK_INT(rb, ==, 0);
  }
  CHECK_INT(trees, >, 5); /* the tree formula was exercised too */
}

/* Random trees of point bodies: each body hangs from an earlier one or the
 * ground. */
static void random_trees_against_brute_force(void) {
  unsigned long long rng = 77;
  for (int trial = 0; trial < 100; trial++) {
    int n = 1 + trial % 16, e[2 * 16];
    for (int v = 0; v < n; v++) e[2 * v] = (int)(test_rnd(&rng) * (v + 1)) - 1, e[2 * v + 1] = v;
    us_Structure *s = graph(n, e, n, NULL);
    CHECK(s);
    us_Count c;
    us_count_subgraphs(s, NULL, &c, NULL);
    int tree = c.is_tree && c.method == US_COUNT_TREE;
    us_count_free(&c);
    int rb = against_brute(s);
    us_structure_free(s);
    CHECK(tree);
    CHECK_INT(rb, ==, 0);
  }
}

/* Past brute force: the two general methods agree on bigger scenes. */
static void frontier_and_contraction_agree(void) {
  us_Structure *sc[3] = {pyramid(7), wall(5, 5), wall(7, 3)};
  int ok = 1;
  for (int i = 0; i < 3; i++) {
    if (!sc[i]) ok = 0;
    if (!sc[i]) continue;
    us_Count a, b;
    char *va = count_value(sc[i], US_COUNT_FRONTIER, &a);
    char *vb = count_value(sc[i], US_COUNT_CONTRACT, &b);
    if (!va || !vb || strcmp(va, vb)) ok = 0, fprintf(stderr, "  scene %d: %s vs %s\n", i, va, vb);
    us_count_free(&a);
    us_count_free(&b);
    us_structure_free(sc[i]);
  }
  CHECK(ok);
}

/* --------------------------------------------------------------- refusals */

static us_CountStatus count_status(const us_Structure *s, const us_CountSettings *set,
                                   int *has_value) {
  us_Count c;
  us_Status st = us_count_subgraphs(s, set, &c, NULL);
  us_CountStatus r = st == US_OK ? c.status : US_COUNT_STATUS_COUNT;
  *has_value = c.value != NULL;
  us_count_free(&c);
  return r;
}

static void refused_at_time_limit(void) {
  us_Structure *s = wall(20, 20);
  CHECK(s);
  us_CountSettings set = us_count_default_settings();
  set.time_limit = 1e-9;
  int hv1, hv2;
  us_CountStatus a = count_status(s, &set, &hv1);
  set.method = US_COUNT_CONTRACT;
  us_CountStatus b = count_status(s, &set, &hv2);
  us_structure_free(s);
  CHECK_INT(a, ==, US_COUNT_REFUSED_TIME);
  CHECK_INT(b, ==, US_COUNT_REFUSED_TIME);
  CHECK(!hv1 && !hv2);
}

static void refused_past_size_and_memory(void) {
  us_Structure *p = pyramid(5), *col = column(6);
  CHECK(p && col);
  us_CountSettings set = us_count_default_settings();
  int hv;
  set.max_bodies = 14;
  us_CountStatus big = count_status(p, &set, &hv);
  set.max_bodies = 15;
  us_CountStatus fits = count_status(p, &set, &hv);
  set.max_tree_bodies = 5;
  us_CountStatus tree = count_status(col, &set, &hv);
  set = us_count_default_settings();
  set.max_memory_mb = 1e-6;
  us_CountStatus mem = count_status(p, &set, &hv);
  set.method = US_COUNT_CONTRACT;
  us_CountStatus mem2 = count_status(p, &set, &hv);
  us_structure_free(p);
  us_structure_free(col);
  CHECK_INT(big, ==, US_COUNT_REFUSED_SIZE);
  CHECK_INT(fits, ==, US_COUNT_EXACT);
  CHECK_INT(tree, ==, US_COUNT_REFUSED_SIZE);
  CHECK_INT(mem, ==, US_COUNT_REFUSED_MEMORY);
  CHECK_INT(mem2, ==, US_COUNT_REFUSED_MEMORY);
}

static void bad_arguments_are_errors(void) {
  us_Structure *p = pyramid(3);
  CHECK(p);
  us_Count c;
  us_Error err;
  us_CountSettings set = us_count_default_settings();
  set.method = US_COUNT_TREE;
  us_Status not_tree = us_count_subgraphs(p, &set, &c, &err);
  us_count_free(&c);
  us_Status not_tree_null = us_count_subgraphs(p, &set, &c, NULL);
  us_count_free(&c);
  set.method = (us_CountMethod)42;
  us_Status bad_method = us_count_subgraphs(p, &set, &c, NULL);
  us_count_free(&c);
  us_structure_free(p);
  CHECK_INT(not_tree, ==, US_ERR_USAGE);
  CHECK(strstr(err.msg, "not a tree") || strstr(err.msg, "cycle"));
  CHECK_INT(not_tree_null, ==, US_ERR_USAGE);
  CHECK_INT(bad_method, ==, US_ERR_USAGE);
  CHECK_INT(us_count_subgraphs(NULL, NULL, &c, NULL), ==, US_ERR_USAGE);
  us_count_free(&c);
  CHECK_INT(us_count_subgraphs(NULL, NULL, NULL, NULL), ==, US_ERR_USAGE);
  us_CountMethod m;
  CHECK(us_count_method_parse("frontier", &m) == 0 && m == US_COUNT_FRONTIER);
  CHECK(us_count_method_parse("bogus", &m) == -1);
  CHECK(!strcmp(us_count_status_name(US_COUNT_REFUSED_TIME), "refused-time"));
}

/* --------------------------------------------------------- out of memory */

/* Fail the k-th allocation for k = 0, 1, ... until the count succeeds:
 * every failure is US_ERR_NOMEM with nothing leaked, the success exact. */
static int oom_sweep(const us_Structure *s, us_CountMethod m, const char *want) {
  us_CountSettings set = us_count_default_settings();
  set.method = m;
  for (long k = 0; k < 100000; k++) {
    long live = us_alloc_fail_after(k);
    us_Count c;
    us_Error err;
    us_Status st = us_count_subgraphs(s, &set, &c, k & 1 ? NULL : &err); /* NULL err too */
    us_alloc_fail_after(-1);
    int ok = st == US_OK ? c.value && !strcmp(c.value, want) : st == US_ERR_NOMEM;
    us_count_free(&c);
    if (!ok || us_alloc_live() != live) {
      fprintf(stderr, "  %s, failing allocation %ld: status %d, live %ld -> %ld\n",
              us_count_method_name(m), k, (int)st, live, us_alloc_live());
      return -1;
    }
    if (st == US_OK) return k > 0 ? 0 : -1; /* some allocation must have been failed */
  }
  return -1;
}

static void out_of_memory_sweeps(void) {
  us_Structure *p = pyramid(4), *l = loose(70), *col = column(5);
  CHECK(p && l && col);
  char want[32];
  snprintf(want, sizeof want, "%llu", (unsigned long long)brute(p));
  int r1 = oom_sweep(p, US_COUNT_FRONTIER, want);
  int r2 = oom_sweep(p, US_COUNT_CONTRACT, want);
  int r3 = oom_sweep(l, US_COUNT_TREE, "1180591620717411303424");
  int r4 = oom_sweep(col, US_COUNT_AUTO, "6");
  us_structure_free(p);
  us_structure_free(l);
  us_structure_free(col);
  CHECK_INT(r1, ==, 0);
  CHECK_INT(r2, ==, 0);
  CHECK_INT(r3, ==, 0);
  CHECK_INT(r4, ==, 0);
}

static void bigint_out_of_memory(void) {
  us_Big a, b;
  us_big_init(&a), us_big_init(&b);
  CHECK(!us_big_set_u64(&a, 3) && !us_big_set_u64(&b, 5));
  for (int i = 0; i < 10; i++) CHECK(!us_big_mul(&a, &a, &a)); /* 3^1024: 26 limbs */
  us_alloc_fail_after(0);
  int m = us_big_mul(&b, &a, &a), add = us_big_add(&b, &a);
  int five = b.n == 1 && b.w[0] == 5; /* a failed call leaves its output as it was */
  int mu = us_big_mul_u64(&b, 7);     /* b has room for 2 limbs: no allocation */
  char *d = us_big_to_dec(&a);
  us_alloc_fail_after(-1);
  int thirty_five = b.n == 1 && b.w[0] == 35;
  us_big_free(&a), us_big_free(&b);
  CHECK_INT(m, ==, -1);
  CHECK_INT(add, ==, -1);
  CHECK(five);
  CHECK_INT(mu, ==, 0);
  CHECK(thirty_five);
  CHECK(d == NULL);
}

US_TEST_MAIN(T(bigint_known_values), T(bigint_products_and_order), T(bigint_out_of_memory),
             T(column_is_a_path), T(column_of_1000), T(loose_blocks_are_a_star),
             T(seventy_loose_blocks_pass_64_bits), T(cycle_through_the_ground),
             T(complete_graph_on_the_ground), T(fixed_pier_is_ground),
             T(floating_part_adds_nothing), T(parts_are_swept_apart), T(pyramids_against_brute_force),
             T(walls_against_brute_force), T(generator_scenes_pinned),
             T(random_graphs_against_brute_force),
             T(random_trees_against_brute_force), T(frontier_and_contraction_agree),
             T(refused_at_time_limit), T(refused_past_size_and_memory),
             T(bad_arguments_are_errors), T(out_of_memory_sweeps))
