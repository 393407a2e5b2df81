/* GRID for lattices: a msocl_model_lattice's 32 neighbours, recomputed
 * from each point's (x, y, z) position, must sum what BUFFER's stored
 * slots sum, bit for bit - under every integrator and both kinds of
 * strain limiting, with each spring set on or left out, with colliders,
 * pins and damping, rows narrower and wider than a work-group, and split
 * over several devices; AUTO must take GRID for an intact lattice, and
 * GRID must refuse a lattice whose springs were changed after the
 * builder. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

/* Spring sets: the builder's default (no body shear), all four sets,
 * and structural springs left out. */
enum { SETS_DEFAULT, SETS_ALL, SETS_NO_STRUCTURAL };
/* Lattices: every set at 5^3, the builder's default and no structural
 * springs (compiled out); fewer layers than the bend springs reach; a
 * single cell; rows of 19 (wider than a work-group). Each runs every
 * method (each new lattice is a new program for PoCL to compile, so the
 * list is short). */
static const struct {
  int size[3], sets;
} cases[] = {{{5, 5, 5}, SETS_ALL}, {{5, 5, 5}, SETS_DEFAULT},
             {{3, 6, 2}, SETS_NO_STRUCTURAL}, {{2, 2, 2}, SETS_DEFAULT},
             {{19, 3, 4}, SETS_ALL}};

/* A lattice dropped onto a floor beside a ball and a round table, one
 * corner pinned, with dashpots, viscous damping and air resistance. */
static msocl_model *busy_lattice(const int *size, int sets)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = size[0];
  d.ny = size[1];
  d.nz = size[2];
  d.origin[1] = 0.01f;
  if (sets == SETS_ALL)
    d.k_shear_body = 80.0f;
  if (sets == SETS_NO_STRUCTURAL)
    d.k_structural = 0.0f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  const float top[3] = {0.0f, -0.02f, 0.0f}, ball[3] = {0.05f, 0.0f, 0.05f};
  const float up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_table(m, top, 0.05f, 0.3f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_sphere(m, ball, 0.03f, 0.5f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_plane(m, up, -0.05f, 0.2f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 1e-4f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.999f), MSOCL_OK);
  return m;
}

struct state {
  int n;
  msocl_layout layout;
  float *pos, *vel;
  msocl_energy e;
};

/* `steps` steps (in calls of 7, so calls end mid-way) on `parts` devices
 * of runtime r; the blow-up check off, so that a run that grows still
 * compares. */
static struct state run(msocl_runtime *r, const msocl_model *m,
                        msocl_layout lay, msocl_integrator in,
                        msocl_strain strain, int fused, int parts, int steps)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 5e-5f;
  o.tuning.layout = lay;
  o.integrator = in;
  o.strain = strain;
  o.tuning.fused = fused ? MSOCL_ON : MSOCL_OFF;
  o.tuning.ndevices = parts;
  o.check_every = 0;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, r, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "sim_create: %s", msocl_last_error());
  msocl_layout got;
  ck_assert_int_eq(msocl_sim_layout(s, &got), MSOCL_OK);
  if (lay != MSOCL_LAYOUT_AUTO)
    ck_assert_int_eq(got, lay);
  for (int done = 0; done < steps; done += 7) {
    rc = msocl_sim_step(s, steps - done < 7 ? steps - done : 7);
    ck_assert_msg(rc == MSOCL_OK, "step: %s", msocl_last_error());
  }
  struct state st;
  msocl_sim_point_count(s, &st.n);
  st.layout = got;
  st.pos = malloc(3 * (size_t)st.n * sizeof(float));
  st.vel = malloc(3 * (size_t)st.n * sizeof(float));
  ck_assert_int_eq(msocl_sim_read_positions(s, st.pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, st.vel), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_energy(s, &st.e), MSOCL_OK);
  msocl_sim_destroy(s);
  return st;
}

/* b must be a's bits: positions, velocities and (on as many devices,
 * which add their parts in the same order) the energy sums. */
static void same(struct state a, struct state b, int energy, const char *what)
{
  const size_t bytes = 3 * (size_t)a.n * sizeof(float);
  ck_assert_msg(memcmp(a.pos, b.pos, bytes) == 0,
                "%s: positions differ by %g", what,
                scene_max_diff(a.pos, b.pos, 3 * a.n));
  ck_assert_msg(memcmp(a.vel, b.vel, bytes) == 0,
                "%s: velocities differ by %g", what,
                scene_max_diff(a.vel, b.vel, 3 * a.n));
  ck_assert_msg(!energy || (a.e.total == b.e.total && a.e.spring == b.e.spring),
                "%s: energy %.17g J against %.17g J", what, b.e.total,
                a.e.total);
}

static void state_free(struct state *st)
{
  free(st->pos);
  free(st->vel);
}

static const struct {
  msocl_integrator in;
  msocl_strain strain;
  int fused;
  const char *name;
} methods[] = {
    {MSOCL_SYMPLECTIC_EULER, MSOCL_STRAIN_NONE, 0, "symplectic Euler"},
    {MSOCL_SYMPLECTIC_EULER, MSOCL_STRAIN_NONE, 1, "fused"},
    {MSOCL_VERLET, MSOCL_STRAIN_NONE, 0, "Verlet"},
    {MSOCL_RK4, MSOCL_STRAIN_NONE, 0, "RK4"},
    {MSOCL_EXPLICIT_EULER, MSOCL_STRAIN_NONE, 0, "explicit Euler"},
    {MSOCL_IMPLICIT_EULER, MSOCL_STRAIN_NONE, 0, "implicit Euler"},
    {MSOCL_SYMPLECTIC_EULER, MSOCL_STRAIN_PROVOT, 0, "Provot strain"},
    {MSOCL_SYMPLECTIC_EULER, MSOCL_STRAIN_VELOCITY, 0, "velocity strain"},
};

/* Each lattice, every method: GRID is BUFFER, bit for bit; AUTO takes
 * GRID for the intact lattice. */
START_TEST(grid_is_buffer)
{
  const int *size = cases[_i].size;
  const int sets = cases[_i].sets;
  msocl_model *m = busy_lattice(size, sets);
  int n = 0;
  msocl_model_point_count(m, &n);
  float *p0 = malloc(3 * (size_t)n * sizeof(float));
  msocl_model_get_positions(m, p0);
  for (size_t q = 0; q < sizeof methods / sizeof methods[0]; q++) {
    char what[160];
    snprintf(what, sizeof what, "%dx%dx%d lattice, sets %d, %s", size[0],
             size[1], size[2], sets, methods[q].name);
    struct state g = run(rt, m, MSOCL_LAYOUT_GRID, methods[q].in,
                         methods[q].strain, methods[q].fused, 1, 100);
    struct state b = run(rt, m, MSOCL_LAYOUT_BUFFER, methods[q].in,
                         methods[q].strain, methods[q].fused, 1, 100);
    same(b, g, 1, what);
    /* it must have moved, or equality proves nothing */
    ck_assert_msg(scene_max_diff(p0, b.pos, 3 * n) > 1e-5, "%s: still",
                  what);
    if (_i == 0) { /* AUTO: GRID, the lattice being intact */
      struct state c = run(rt, m, MSOCL_LAYOUT_AUTO, methods[q].in,
                           methods[q].strain, methods[q].fused, 1, 0);
      ck_assert_msg(c.layout == MSOCL_LAYOUT_GRID, "%s: AUTO took layout %d",
                    what, (int)c.layout);
      state_free(&c);
    }
    state_free(&b);
    state_free(&g);
  }
  free(p0);
  msocl_model_destroy(m);
}
END_TEST

/* Split over two and three devices (as many as there are): GRID is the
 * one-device run, for symplectic Euler and RK4. */
START_TEST(split_is_one_device)
{
  char spec[256];
  const int ndev = scene_cpu_spec(spec, sizeof spec, 3);
  if (ndev < 2) {
    printf("split_is_one_device: one CPU device only, nothing to split\n");
    return;
  }
  msocl_runtime *many = NULL;
  ck_assert_int_eq(msocl_runtime_create(&many, spec), MSOCL_OK);
  const int size[3] = {6, 5, 9};
  msocl_model *m = busy_lattice(size, SETS_ALL);
  /* symplectic Euler and RK4: each split compiles every kernel again for
   * its ranges' sizes, so the list is short (check_multidevice runs every
   * integrator split on cloths) */
  static const int split_methods[2] = {0, 3};
  for (int u = 0; u < 2; u++) {
    const int q = split_methods[u];
    struct state one = run(many, m, MSOCL_LAYOUT_GRID, methods[q].in,
                           MSOCL_STRAIN_NONE, 0, 1, 100);
    for (int parts = 2; parts <= ndev; parts++) {
      char what[160];
      snprintf(what, sizeof what, "%s on %d devices", methods[q].name,
               parts);
      struct state split = run(many, m, MSOCL_LAYOUT_GRID, methods[q].in,
                               MSOCL_STRAIN_NONE, 0, parts, 100);
      same(one, split, 0, what);
      state_free(&split);
    }
    state_free(&one);
  }
  /* AUTO takes GRID on a split as on one device */
  struct state a = run(many, m, MSOCL_LAYOUT_AUTO, MSOCL_SYMPLECTIC_EULER,
                       MSOCL_STRAIN_NONE, 0, 2, 0);
  ck_assert_int_eq(a.layout, MSOCL_LAYOUT_GRID);
  state_free(&a);
  msocl_model_destroy(m);
  msocl_runtime_destroy(many);
}
END_TEST

/* GRID recomputes springs from the builder's record: a spring or a point
 * added after it must turn GRID away with a clear error (AUTO then takes
 * BUFFER, and the added point moves as BUFFER moves it). */
START_TEST(changed_lattice_refused)
{
  const int size[3] = {3, 3, 3};
  msocl_model *m = busy_lattice(size, SETS_DEFAULT);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_sim_destroy(s);
  if (_i == 0) {
    const int ij[2] = {0, 26};
    const float k = 1.0f;
    ck_assert_int_eq(msocl_model_add_springs(m, 1, ij, &k, NULL, NULL),
                     MSOCL_OK);
  } else { /* a loose point above the cube: it falls */
    const float xyz[3] = {0.0f, 0.2f, 0.0f}, mass = 0.002f;
    ck_assert_int_eq(msocl_model_add_points(m, 1, xyz, &mass, NULL),
                     MSOCL_OK);
  }
  s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_msg(strstr(msocl_last_error(), "lattice") &&
                    strstr(msocl_last_error(), _i ? "points" : "springs"),
                "unclear error: %s", msocl_last_error());
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_layout got;
  ck_assert_int_eq(msocl_sim_layout(s, &got), MSOCL_OK);
  ck_assert_int_eq(got, MSOCL_LAYOUT_BUFFER);
  if (_i == 1) {
    float p[3 * 28];
    ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
    ck_assert_msg(p[3 * 27 + 1] < 0.2f, "the added point did not fall");
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_lattice");
  Suite *su = suite_create("lattice");
  TCase *tc = tcase_create("lattice");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_loop_test(tc, grid_is_buffer, 0,
                      (int)(sizeof cases / sizeof cases[0]));
  tcase_add_test(tc, split_is_one_device);
  tcase_add_loop_test(tc, changed_lattice_refused, 0, 2);
  suite_add_tcase(su, tc);
  return scene_run(su);
}
