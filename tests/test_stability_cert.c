/* Tests of the independent certificate check: it accepts forces balanced by
 * hand (lever rule on a point body), and rejects tampered solver forces:
 * a flipped normal, a scaled force, a force moved to an inactive contact, a
 * duplicated contact, friction outside the cone, swapped forces (right
 * total, wrong torque) and non-finite values. */
#include "stability/backend.h"
#include "stability/certificate.h"
#include "stability/lp_gen.h"
#include "scenes.h"
#include "test.h"

/* Point body of mass m at (cx, 0.5) on ground contacts at xl < xr. */
static us_Structure *lever(double m, double cx, double xl, double xr, double mu) {
  us_Structure *s = us_structure_new(2);
  us_Error err;
  double c[2] = {cx, 0.5}, up[2] = {0, 1}, pl[2] = {xl, 0}, pr[2] = {xr, 0};
  int b = us_structure_add_point_body(s, "p", m, c, 0, &err);
  us_structure_add_contact(s, US_GROUND, b, pl, up, mu, &err);
  us_structure_add_contact(s, US_GROUND, b, pr, up, mu, &err);
  s->explicit_contacts = 1;
  if (us_structure_finalize(s, &err) != US_OK) {
    us_structure_free(s);
    return NULL;
  }
  return s;
}

/* Lever rule: f_r = m g (cx - xl) / (xr - xl), f_l = m g - f_r. */
static void hand_forces(us_Forces *f, double m, double cx, double xl, double xr) {
  double W = m * 9.81, fr = W * (cx - xl) / (xr - xl);
  f->ncontact = 2;
  f->contact[0] = 0;
  f->contact[1] = 1;
  f->f[0] = W - fr;
  f->f[1] = 0.0;
  f->f[2] = fr;
  f->f[3] = 0.0;
}

static void accepts_hand_solution(void) {
  us_Structure *s = lever(3.0, 0.2, -0.5, 0.5, 0.0);
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, 1) == 0);
  us_bitset_fill(&p);
  int ci[2];
  double fv[4];
  us_Forces f = {2, 2, ci, fv};
  hand_forces(&f, 3.0, 0.2, -0.5, 0.5);
  us_CertCheck c = us_certificate_check(s, &p, &f, 1e-9);
  CHECK(c.ok);
  CHECK(c.max_force_residual <= 1e-12 && c.max_torque_residual <= 1e-12);
  CHECK_INT(c.worst_contact, ==, -1); /* nothing violated */
  /* swapped: the total is right, the torque is not */
  double t = fv[0];
  fv[0] = fv[2];
  fv[2] = t;
  c = us_certificate_check(s, &p, &f, 1e-6);
  CHECK(!c.ok);
  CHECK(c.max_force_residual <= 1e-12);
  CHECK(c.max_torque_residual > 1e-3);
  CHECK_INT(c.worst_body, ==, 0);
  /* the body absent: the contacts are inactive, forces on them are wrong */
  hand_forces(&f, 3.0, 0.2, -0.5, 0.5);
  us_bitset_clear(&p, 0);
  c = us_certificate_check(s, &p, &f, 1e-6);
  CHECK(!c.ok);
  us_bitset_free(&p);
  us_structure_free(s);
}

/* Friction: a tangential pair that cancels (balanced) is inside the cone
 * only if mu allows it. */
static void cone_and_sign(void) {
  us_Structure *s = lever(1.0, 0.0, -0.5, 0.5, 0.3);
  CHECK(s);
  us_Bitset p;
  CHECK(us_bitset_init(&p, 1) == 0);
  us_bitset_fill(&p);
  int ci[2];
  double fv[4];
  us_Forces f = {2, 2, ci, fv};
  hand_forces(&f, 1.0, 0.0, -0.5, 0.5);
  double fn = fv[0];
  fv[1] = 0.2 * fn; /* squeeze: +t on one side, -t on the other */
  fv[3] = -0.2 * fn;
  us_CertCheck c = us_certificate_check(s, &p, &f, 1e-9);
  CHECK(c.ok); /* 0.2 <= mu = 0.3 */
  fv[1] = 0.5 * fn;
  fv[3] = -0.5 * fn;
  c = us_certificate_check(s, &p, &f, 1e-6);
  CHECK(!c.ok);
  CHECK(c.max_cone_violation > 0.05); /* (0.5 - 0.3) * W / 2 / W = 0.1 */
  CHECK(c.worst_contact == 0 || c.worst_contact == 1);
  CHECK(c.max_force_residual <= 1e-12);
  /* a pulling contact balanced by a bigger push: sign violation */
  hand_forces(&f, 1.0, 0.0, -0.5, 0.5);
  fv[0] = -1.0;
  fv[2] = 9.81 + 1.0;
  c = us_certificate_check(s, &p, &f, 1e-6);
  CHECK(!c.ok);
  CHECK(c.max_sign_violation > 0.05);
  /* non-finite */
  hand_forces(&f, 1.0, 0.0, -0.5, 0.5);
  fv[1] = NAN;
  c = us_certificate_check(s, &p, &f, 1e-6);
  CHECK(!c.ok);
  us_bitset_free(&p);
  us_structure_free(s);
}

/* Solver forces of a 2 x 2 brick stack minus its top-right brick. */
static void tampered_solver_forces(void) {
  us_Structure *s = us_structure_new(2);
  scene_box(s, "a", 0, 0, 1, 0.5, 1);
  scene_box(s, "b", 1, 0, 1, 0.5, 1);
  scene_box(s, "c", 0.25, 0.5, 1, 0.5, 1);
  scene_box(s, "d", 1.25, 0.5, 0.5, 0.5, 1);
  us_Error err;
  CHECK_OK(us_structure_finalize(s, &err), &err);
  us_Bitset p;
  CHECK(us_bitset_init(&p, 4) == 0);
  us_bitset_fill(&p);
  us_bitset_clear(&p, 3);
  for (int m = 0; m < 2; m++) {
    us_StabilitySettings set = us_stability_default_settings();
    set.method = m ? US_METHOD_LPSOLVE : US_METHOD_LP;
    us_Stability *w = us_stability_new(s, &set, &err);
    CHECK(w);
    us_StabilityResult res = {0};
    CHECK_OK(us_stability_test(w, &p, &res, &err), &err);
    CHECK_INT(res.verdict, ==, US_STABLE);
    us_Forces *f = &res.forces;
    CHECK(us_certificate_check(s, &p, f, 1e-6).ok);
    /* the force with the largest normal */
    int big = 0;
    for (int i = 1; i < f->ncontact; i++)
      if (f->f[2 * i] > f->f[2 * big]) big = i;
    CHECK(f->f[2 * big] > 0.1 * s->weight / f->ncontact);
    double save[2] = {f->f[2 * big], f->f[2 * big + 1]};
    f->f[2 * big] = -save[0];
    CHECK(!us_certificate_check(s, &p, f, 1e-6).ok);
    f->f[2 * big] = 1.5 * save[0];
    f->f[2 * big + 1] = 1.5 * save[1];
    us_CertCheck c = us_certificate_check(s, &p, f, 1e-6);
    CHECK(!c.ok);
    CHECK(c.max_force_residual > 1e-3);
    f->f[2 * big] = save[0];
    f->f[2 * big + 1] = save[1];
    CHECK(us_certificate_check(s, &p, f, 1e-6).ok);
    /* move it to a contact of the absent brick d */
    int inactive = -1;
    for (int c2 = 0; c2 < s->ncontact; c2++)
      if (s->contacts[c2].a == 3 || s->contacts[c2].b == 3) inactive = c2;
    CHECK(inactive >= 0);
    int orig = f->contact[big];
    f->contact[big] = inactive;
    c = us_certificate_check(s, &p, f, 1e-6);
    CHECK(!c.ok);
    CHECK_INT(c.worst_contact, ==, inactive);
    /* list a contact twice */
    f->contact[big] = f->contact[big == 0 ? 1 : 0];
    CHECK(!us_certificate_check(s, &p, f, 1e-6).ok);
    f->contact[big] = orig;
    CHECK(us_certificate_check(s, &p, f, 1e-6).ok);
    us_stability_result_free(&res);
    us_stability_free(w);
  }
  us_bitset_free(&p);
  us_structure_free(s);
}

/* Residuals are measured against each body's own weight, load and size,
 * not against the whole structure: a light body far from a heavy one,
 * with 1 % of its weight missing or 1 % of its weight times its size of
 * torque left over, fails the check although both errors are below 1e-6
 * of the whole structure's weight times its size. (The first version of
 * the check measured against the whole and certified an unstable
 * 1,256-block stack this way.) */
static void light_body_own_scale(void) {
  us_Structure *s = us_structure_new(2);
  us_Error err;
  double up[2] = {0, 1};
  double ch[2] = {200.0, 0.5}, cl[2] = {0.2, 0.5};
  int h = us_structure_add_point_body(s, "heavy", 1e6, ch, 0, &err);
  int l = us_structure_add_point_body(s, "light", 1.0, cl, 0, &err);
  double p[4][2] = {{199.5, 0}, {200.5, 0}, {-0.5, 0}, {0.5, 0}};
  for (int k = 0; k < 4; k++) us_structure_add_contact(s, US_GROUND, k < 2 ? h : l, p[k], up, 0.0, &err);
  s->explicit_contacts = 1;
  CHECK(us_structure_finalize(s, &err) == US_OK);
  us_Bitset pr;
  CHECK(us_bitset_init(&pr, 2) == 0);
  us_bitset_fill(&pr);
  int ci[4] = {0, 1, 2, 3};
  double fv[8] = {0};
  us_Forces f = {4, 4, ci, fv};
  double wh = 1e6 * 9.81, wl = 9.81;
  fv[0] = fv[2] = wh / 2;             /* heavy: centred */
  fv[6] = wl * (0.2 + 0.5);           /* light: lever rule, xl = -0.5, xr = 0.5 */
  fv[4] = wl - fv[6];
  us_CertCheck c = us_certificate_check(s, &pr, &f, 1e-6);
  CHECK(c.ok);
  /* 1 % of the light body's weight missing */
  fv[4] -= 0.01 * wl;
  c = us_certificate_check(s, &pr, &f, 1e-6);
  CHECK(!c.ok);
  CHECK_INT(c.worst_body, ==, l);
  CHECK(c.max_force_residual > 1e-3);
  /* the right total, 1 % of weight x size of torque left over */
  fv[4] += 0.01 * wl + 0.005 * wl;
  fv[6] -= 0.005 * wl;
  c = us_certificate_check(s, &pr, &f, 1e-6);
  CHECK(!c.ok);
  CHECK_INT(c.worst_body, ==, l);
  CHECK(c.max_force_residual <= 1e-12 && c.max_torque_residual > 1e-3);
  us_bitset_free(&pr);
  us_structure_free(s);
}

US_TEST_MAIN(T(accepts_hand_solution), T(cone_and_sign), T(tampered_solver_forces),
             T(light_body_own_scale))
