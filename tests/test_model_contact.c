/* Tests of contact detection (src/contact) through us_structure_finalize. */
#include "model/model.h"
#include "test.h"

static int add_box(us_Structure *s, const char *id, double x0, double y0, double x1, double y1,
                   us_Error *err) {
  double xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
  return us_structure_add_polygon(s, id, 4, xy, 1.0, 0.0, 0, -1.0, err);
}

static void block_on_ground(void) {
  us_Error err;
  us_Structure *s = us_structure_new(2);
  CHECK(add_box(s, "b0", 0, 0, 2, 1, &err) == 0);
  CHECK_OK(us_structure_finalize(s, &err), &err);
  CHECK_INT(s->ncontact, ==, 2);
  for (int k = 0; k < s->ncontact; k++) {
    CHECK_INT(s->contacts[k].a, ==, US_GROUND);
    CHECK_NEAR(s->contacts[k].n[1], 1.0, 1e-12);
  }
  us_structure_free(s);
}

US_TEST_MAIN(T(block_on_ground))
