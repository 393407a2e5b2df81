/* BUFFER's slot table and its spill: a point's springs past the table's
 * width go in a list of its own, summed in the same order, so any width
 * gives bitwise the same motion; a hub point (a solid's centre, joined to
 * every surface point) no longer makes the table hub-degree x points.
 * And its spring classes: a slot's byte naming its (rest, k, dashpot),
 * bitwise the values in every slot. */
#include "layout.h" /* msocl__table_slots */
#include "scenes.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

static void add_ground(msocl_model *m)
{
  const float up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_plane(m, up, 0.0f, 0.5f), MSOCL_OK);
}

/* The default soft ball (162 surface points and a centre joined to all),
 * dropped on the ground. */
static msocl_model *ball(void)
{
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_solid(&m, &d), MSOCL_OK);
  add_ground(m);
  return m;
}

/* A small damped jello cube: degree 24, dashpots on every spring. */
static msocl_model *jello(void)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = d.ny = d.nz = 5;
  d.damping = 0.05f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  add_ground(m);
  return m;
}

struct state {
  int n;
  int classes; /* the sim's spring classes (0: values in the slots) */
  float *pos, *vel;
};

/* table: tuning.buffer_slots; classes: tuning.classes ON (1) or OFF (0) */
static struct state run_classes(const msocl_model *m, msocl_integrator in,
                                int table, int classes, int steps)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.layout = MSOCL_LAYOUT_BUFFER;
  o.integrator = in;
  o.tuning.buffer_slots = table;
  o.tuning.classes = classes ? MSOCL_ON : MSOCL_OFF;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt),
                   MSOCL_OK);
  float edt;
  /* forward Euler's own, tighter limit (dashpots make it finite) */
  if (in == MSOCL_EXPLICIT_EULER &&
      msocl_stable_dt(m, MSOCL_EXPLICIT_EULER, &edt) == MSOCL_OK && edt < o.dt)
    o.dt = edt;
  o.dt *= 0.5f;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  rc = msocl_sim_step(s, steps);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  struct state st;
  msocl_sim_point_count(s, &st.n);
  ck_assert_int_eq(msocl_sim_connectivity(s, NULL, &st.classes), MSOCL_OK);
  st.pos = malloc(3 * (size_t)st.n * sizeof(float));
  st.vel = malloc(3 * (size_t)st.n * sizeof(float));
  ck_assert_int_eq(msocl_sim_read_positions(s, st.pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, st.vel), MSOCL_OK);
  msocl_sim_destroy(s);
  return st;
}

static struct state run(const msocl_model *m, msocl_integrator in,
                        int table, int steps)
{
  return run_classes(m, in, table, 1, steps);
}

static void same(struct state a, struct state b, const char *what)
{
  const size_t bytes = 3 * (size_t)a.n * sizeof(float);
  ck_assert_msg(memcmp(a.pos, b.pos, bytes) == 0 &&
                    memcmp(a.vel, b.vel, bytes) == 0,
                "%s: positions differ by %g, velocities by %g", what,
                scene_max_diff(a.pos, b.pos, 3 * a.n),
                scene_max_diff(a.vel, b.vel, 3 * a.n));
  free(b.pos);
  free(b.vel);
}

static const char *const names[] = {"symplectic Euler", "explicit Euler",
                                    "Verlet", "RK4", "implicit Euler"};

/* _i: the integrator. Every kernel that walks a point's springs (forces,
 * implicit Euler's products, energy for the blow-up check) reads the
 * spill. */
START_TEST(any_width_is_bitwise_the_full_table)
{
  msocl_integrator in = (msocl_integrator)_i;
  if (in == MSOCL_EXPLICIT_EULER)
    return; /* undamped ball: forward Euler grows; the jello covers it */
  msocl_model *m = ball();
  int n, top;
  msocl_model_point_count(m, &n);
  msocl_model_max_degree(m, &top);
  struct state full = run(m, in, top, 200);
  float *p0 = malloc(3 * (size_t)n * sizeof(float));
  msocl_model_get_positions(m, p0);
  ck_assert(scene_max_diff(p0, full.pos, 3 * n) > 1e-3); /* it fell */
  free(p0);
  const int widths[] = {0, 1, 4, 7, 8};
  for (int w = 0; w < 5; w++) {
    char what[96];
    snprintf(what, sizeof what, "ball, %s, table of %d", names[in],
             widths[w]);
    same(full, run(m, in, widths[w], 200), what);
  }
  free(full.pos);
  free(full.vel);
  msocl_model_destroy(m);
}
END_TEST

/* Dashpots read the neighbours' velocities from the spill too. */
START_TEST(damped_lattice_spills_bitwise)
{
  msocl_integrator in = (msocl_integrator)_i;
  msocl_model *m = jello();
  struct state full = run(m, in, 0, 300);
  for (int w = 1; w <= 20; w += 19) {
    char what[96];
    snprintf(what, sizeof what, "jello, %s, table of %d", names[in], w);
    same(full, run(m, in, w, 300), what);
  }
  free(full.pos);
  free(full.vel);
  msocl_model_destroy(m);
}
END_TEST

/* _i: the integrator. Classes against values in every slot: the undamped
 * ball with its hub spilling past a table of 8 (classes in the spill
 * too), and the damped jello (a class holds the dashpot). */
START_TEST(classes_are_bitwise_the_values)
{
  msocl_integrator in = (msocl_integrator)_i;
  msocl_model *m[2] = {in == MSOCL_EXPLICIT_EULER ? NULL : ball(), jello()};
  const int table[2] = {8, 0};
  const char *name[2] = {"ball, table of 8", "damped jello"};
  for (int q = 0; q < 2; q++) {
    if (!m[q])
      continue; /* undamped: forward Euler grows; the jello covers it */
    struct state values = run_classes(m[q], in, table[q], 0, 200);
    struct state classes = run_classes(m[q], in, table[q], 1, 200);
    printf("%s, %s: %d spring classes\n", name[q], names[in],
           classes.classes);
    ck_assert_int_eq(values.classes, 0);
    ck_assert_int_gt(classes.classes, 1);
    char what[96];
    snprintf(what, sizeof what, "%s, %s, classes", name[q], names[in]);
    same(values, classes, what);
    free(values.pos);
    free(values.vel);
    msocl_model_destroy(m[q]);
  }
}
END_TEST

/* A chain whose links all differ in rest length: 256 classes at most (the
 * free slot's zeros and 255 links) fit a byte; one more link, and every
 * slot holds its values again - bitwise the same either way. */
START_TEST(classes_fit_a_byte)
{
  for (int links = 255; links <= 256; links++) {
    msocl_model *m = NULL;
    ck_assert_int_eq(msocl_model_create(&m), MSOCL_OK);
    const int n = links + 1;
    float *xyz = calloc(3 * (size_t)n, sizeof *xyz),
          *mass = malloc((size_t)n * sizeof *mass),
          *k = malloc((size_t)links * sizeof *k),
          *rest = malloc((size_t)links * sizeof *rest);
    int *ij = malloc(2 * (size_t)links * sizeof *ij);
    for (int i = 0; i < n; i++) {
      xyz[3 * i] = 0.01f * (float)i;
      mass[i] = 0.01f;
    }
    for (int s = 0; s < links; s++) {
      ij[2 * s] = s;
      ij[2 * s + 1] = s + 1;
      k[s] = 50.0f;
      rest[s] = 0.009f + 1e-5f * (float)s; /* each its own */
    }
    ck_assert_int_eq(msocl_model_add_points(m, n, xyz, mass, NULL),
                     MSOCL_OK);
    ck_assert_int_eq(msocl_model_add_springs(m, links, ij, k, rest, NULL),
                     MSOCL_OK);
    ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
    struct state values = run_classes(m, MSOCL_SYMPLECTIC_EULER, 0, 0, 300);
    struct state classes = run_classes(m, MSOCL_SYMPLECTIC_EULER, 0, 1, 300);
    ck_assert_int_eq(classes.classes, links == 255 ? 256 : 0);
    char what[64];
    snprintf(what, sizeof what, "chain of %d distinct links", links);
    same(values, classes, what);
    free(values.pos);
    free(values.vel);
    free(xyz); free(mass); free(k); free(rest); free(ij);
    msocl_model_destroy(m);
  }
}
END_TEST

/* tuning.classes = MSOCL_AUTO (the default) takes classes once the table of
 * values (12 B a slot, undamped) outgrows half the device's reported
 * cache: a 16^2 cloth stays with values, a 512^2 one - 38 MB of values
 * on this machine's 36 MiB cache - gets classes. The expectation follows
 * the device's own figure; only the rule is fixed. */
START_TEST(classes_auto)
{
  const int sizes[2] = {16, 512};
  for (int q = 0; q < 2; q++) {
    msocl_model *m = scene_tablecloth(sizes[q]);
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    ck_assert_int_eq(o.tuning.classes, MSOCL_AUTO);
    o.tuning.layout = MSOCL_LAYOUT_BUFFER;
    o.dt = 1e-4f;
    msocl_sim *s = NULL;
    int rc = msocl_sim_create(&s, rt, m, &o);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    int slots, classes, n;
    msocl_device_info info;
    ck_assert_int_eq(msocl_sim_connectivity(s, &slots, &classes), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_device_info(s, &info), MSOCL_OK);
    msocl_sim_point_count(s, &n);
    double values = 12.0 * slots * n;
    printf("%dx%d cloth: %.1f MB of values, cache %.1f MiB: %d classes\n",
           sizes[q], sizes[q], values / 1e6, (double)info.cache / 1048576.0,
           classes);
    if (values > 0.5 * (double)info.cache)
      ck_assert_int_gt(classes, 1);
    else
      ck_assert_int_eq(classes, 0);
    msocl_sim_destroy(s);
    msocl_model_destroy(m);
  }
  msocl_model *m = scene_tablecloth(8);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.classes = (msocl_choice)3;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_model_destroy(m);
}
END_TEST

/* The width chosen from the degrees: the whole table where degrees are
 * alike; past a hub, the 99% of points' width. */
START_TEST(width_from_degrees)
{
  msocl_model *m = ball();
  struct msocl__adjacency a;
  ck_assert_int_eq(msocl__adjacency_build(m, &a), MSOCL_OK);
  int w = msocl__table_slots(&a, 0);
  printf("ball: %d points, largest degree %d (the centre), table of %d\n",
         a.n, a.max_degree, w);
  ck_assert_int_eq(a.max_degree, a.n - 1);
  ck_assert_int_eq(w % 4, 0);
  ck_assert(w >= 6 && w <= 12); /* a surface point: ~6 edges + centre */
  ck_assert_int_eq(msocl__table_slots(&a, 3), 3);
  /* past the largest degree or the widest table the kernels unroll */
  ck_assert_int_eq(a.max_degree, 162);
  ck_assert_int_eq(msocl__table_slots(&a, 100000), MSOCL__TABLE_SLOTS);
  ck_assert_int_eq(msocl__table_slots(&a, 100), MSOCL__TABLE_SLOTS);
  msocl__adjacency_free(&a);
  msocl_model_destroy(m);

  m = jello();
  ck_assert_int_eq(msocl__adjacency_build(m, &a), MSOCL_OK);
  ck_assert_int_eq(msocl__table_slots(&a, 0), a.max_degree); /* 24 */
  msocl__adjacency_free(&a);

  msocl_sim_options o;
  msocl_sim_options_init(&o);
  ck_assert_int_eq(o.tuning.buffer_slots, 0);
  o.dt = 1e-4f;
  o.tuning.buffer_slots = -1;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_model_destroy(m);
}
END_TEST

/* The ball split over two devices: the hub's springs spill, the points
 * are renumbered, and the hub's halo reaches every point - bitwise the
 * one-device run all the same. */
START_TEST(split_ball_bitwise)
{
  char spec[128];
  if (scene_cpu_spec(spec, sizeof spec, 2) < 2) {
    printf("split_ball_bitwise: one CPU device only; not split\n");
    return;
  }
  msocl_runtime *two = NULL;
  ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
  msocl_model *m = ball();
  int n;
  msocl_model_point_count(m, &n);
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  float *p[2], *v[2];
  for (int parts = 1; parts <= 2; parts++) {
    msocl_sim_options o;
    msocl_sim_options_init(&o);
    o.tuning.layout = MSOCL_LAYOUT_BUFFER;
    o.tuning.ndevices = parts;
    ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt),
                     MSOCL_OK);
    o.dt *= 0.5f;
    msocl_sim *s = NULL;
    int rc = msocl_sim_create(&s, two, m, &o);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    ck_assert_int_eq(msocl_sim_step(s, 200), MSOCL_OK);
    p[parts - 1] = malloc(bytes);
    v[parts - 1] = malloc(bytes);
    ck_assert_int_eq(msocl_sim_read_positions(s, p[parts - 1]), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_velocities(s, v[parts - 1]), MSOCL_OK);
    msocl_sim_destroy(s);
  }
  ck_assert_msg(memcmp(p[0], p[1], bytes) == 0 && memcmp(v[0], v[1], bytes) == 0,
                "split ball differs: positions by %g, velocities by %g",
                scene_max_diff(p[0], p[1], 3 * n),
                scene_max_diff(v[0], v[1], 3 * n));
  for (int q = 0; q < 2; q++) {
    free(p[q]);
    free(v[q]);
  }
  msocl_model_destroy(m);
  msocl_runtime_destroy(two);
}
END_TEST

/* Before the spill a 40962-point ball asked for a 40962-slot table: 6.7
 * GB of connectivity, refused by the device. */
START_TEST(big_ball_fits)
{
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  d.subdivisions = 6;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_solid(&m, &d), MSOCL_OK);
  add_ground(m);
  struct state st = run(m, MSOCL_SYMPLECTIC_EULER, 0, 5);
  printf("ball of %d points: 5 steps run\n", st.n);
  for (int i = 0; i < 3 * st.n; i++)
    ck_assert(st.pos[i] == st.pos[i]); /* finite, not NaN */
  free(st.pos);
  free(st.vel);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  scene_require_device("check_spill");
  Suite *su = suite_create("spill");
  TCase *tc = tcase_create("spill");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, width_from_degrees);
  tcase_add_loop_test(tc, any_width_is_bitwise_the_full_table,
                      MSOCL_SYMPLECTIC_EULER, MSOCL_IMPLICIT_EULER + 1);
  tcase_add_loop_test(tc, damped_lattice_spills_bitwise,
                      MSOCL_SYMPLECTIC_EULER, MSOCL_IMPLICIT_EULER + 1);
  tcase_add_loop_test(tc, classes_are_bitwise_the_values, 0, 5);
  tcase_add_test(tc, classes_fit_a_byte);
  tcase_add_test(tc, classes_auto);
  tcase_add_test(tc, split_ball_bitwise);
  tcase_add_test(tc, big_ball_fits);
  suite_add_tcase(su, tc);
  return scene_run(su);
}
