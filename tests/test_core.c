/* Tests of src/core: bitsets, the bitset hash set, the allocation funnel. */
#include "core/core.h"
#include "test.h"

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

US_TEST_MAIN(T(bitset_basics), T(bitset_set_many), T(alloc_failure_hook), T(error_messages))
