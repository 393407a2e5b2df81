/* The one engine (x, y, z planes of floats) on every layout: a cloth
 * grid's symplectic Euler steps (two passes or fused), Verlet and RK4
 * steps on GRID must be bitwise BUFFER's - with every feature the GRID
 * kernels compile in (colliders of each kind, pins, dashpots, viscous
 * damping, air), grids narrower and wider than a work-group, and the state
 * written between calls - and AUTO must take GRID exactly where it
 * applies, and not where its padding would multiply the memory (a skinny
 * lattice); a grid too large for the kernels' int indices is refused
 * before anything is allocated. BUFFER and IMAGE2D are bitwise each other
 * (or BUFFER a narrower, spilling table, or without spring classes), for
 * every integrator and strain limit, on a cloth, a lattice, an irregular
 * mesh from OBJ text and a ball (its hub in a wide table, or spilling past
 * a narrow one). */
#include "scenes.h"
#include "sim.h" /* msocl__planes_bytes, _refused, _would, layout_auto */

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define rt scene_rt

static msocl_model *obj_sheet(int nx, int ny);

/* An nx x ny cloth with everything the GRID kernels handle: a round
 * table, a ball beside it and a floor under both, a pinned corner,
 * dashpots, viscous damping and air resistance. */
static msocl_model *busy_cloth(int nx, int ny)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  d.origin[0] = -0.5f;
  d.origin[1] = 0.05f;
  d.origin[2] = -0.5f;
  d.u[0] = 0.0f; d.u[1] = 0.0f; d.u[2] = 1.0f;
  d.v[0] = 1.0f; d.v[1] = 0.0f; d.v[2] = 0.0f;
  d.point_mass = 0.5f / (float)(nx * ny);
  d.k_stretch = 50.0f;
  d.k_shear = 10.0f;
  d.k_bend = 10.0f;
  d.damping = 1e-3f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  const float top[3] = {-0.1f, 0.0f, 0.0f}, ball[3] = {0.35f, -0.05f, 0.1f};
  const float up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_table(m, top, 0.3f, 0.3f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_sphere(m, ball, 0.15f, 0.5f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_plane(m, up, -0.2f, 0.2f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, nx * ny - 1, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 1e-4f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.999f), MSOCL_OK);
  return m;
}

struct state {
  int n;
  float *pos, *vel;
};

static void state_free(struct state *st)
{
  free(st->pos);
  free(st->vel);
}

/* The layout, spring classes (-1 AUTO, 0 OFF, 1 ON) and table width the
 * tested sims get (the mesh cases set them; GRID otherwise). */
struct setup {
  msocl_layout layout;
  int classes, slots;
  int sweep; /* tuning.sweep_steps */
};
static struct setup setup_ = {MSOCL_LAYOUT_GRID, -1, 0, 0};

/* The setup a tested one is held to, which must step bitwise alike: GRID
 * and IMAGE2D against BUFFER's plain table (no classes); BUFFER with
 * classes against the same table without; a plain BUFFER against IMAGE2D
 * where m's points fit the texture's 16 slots, else against a table of 8
 * slots that spills (and one that already spills against its full
 * table). */
static struct setup held_setup(const msocl_model *m, struct setup t)
{
  struct setup h = {MSOCL_LAYOUT_BUFFER, 0, 0, 0};
  if (t.layout != MSOCL_LAYOUT_BUFFER)
    return h;
  if (t.classes == 1) {
    h.slots = t.slots;
    return h;
  }
  int degree = 0;
  ck_assert_int_eq(msocl_model_max_degree(m, &degree), MSOCL_OK);
  if (t.slots > 0 && t.slots < degree)
    h.slots = 64; /* every spring in the table: at most 64 slots */
  else if (degree <= 16)
    h.layout = MSOCL_LAYOUT_IMAGE2D;
  else
    h.slots = 8;
  return h;
}

/* mode: 1 symplectic Euler's two passes, 2 fused; 3 Verlet, 4 RK4, 5
 * implicit Euler, 6 explicit Euler. held: in held_setup's setup (and
 * two passes for fused, as a gather in two passes is what fused must
 * equal), else in setup_. */
static msocl_sim *make_strained(const msocl_model *m, int held, int mode,
                                msocl_math math, float dt,
                                msocl_strain strain)
{
  const struct setup t = held ? held_setup(m, setup_) : setup_;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.classes =
      t.classes < 0 ? MSOCL_AUTO : t.classes ? MSOCL_ON : MSOCL_OFF;
  o.tuning.buffer_slots = t.slots;
  o.tuning.sweep_steps = t.sweep;
  o.strain = strain;
  o.strain_iterations = 3; /* the sweeps ping-pong */
  if (mode >= 3) {
    static const msocl_integrator in[4] = {
        MSOCL_VERLET, MSOCL_RK4, MSOCL_IMPLICIT_EULER, MSOCL_EXPLICIT_EULER};
    o.integrator = in[mode - 3];
  }
  o.tuning.layout = t.layout;
  o.tuning.fused = mode == 2 && !held ? MSOCL_ON : MSOCL_OFF;
  o.math = math;
  o.dt = dt;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  msocl_layout ran = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_layout(s, &ran), MSOCL_OK);
  ck_assert_int_eq(ran, t.layout);
  return s;
}

static msocl_sim *make(const msocl_model *m, int held, int mode,
                       msocl_math math, float dt)
{
  return make_strained(m, held, mode, math, dt, MSOCL_STRAIN_NONE);
}

static struct state read_state(msocl_sim *s)
{
  struct state st;
  ck_assert_int_eq(msocl_sim_point_count(s, &st.n), MSOCL_OK);
  st.pos = malloc(3 * (size_t)st.n * sizeof(float));
  st.vel = malloc(3 * (size_t)st.n * sizeof(float));
  ck_assert_int_eq(msocl_sim_read_positions(s, st.pos), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_read_velocities(s, st.vel), MSOCL_OK);
  return st;
}

/* `calls` calls of `steps` steps each. */
static struct state run_strained(const msocl_model *m, int held, int mode,
                                 msocl_math math, float dt, int calls,
                                 int steps, msocl_strain strain)
{
  msocl_sim *s = make_strained(m, held, mode, math, dt, strain);
  for (int c = 0; c < calls; c++) {
    int rc = msocl_sim_step(s, steps);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  }
  struct state st = read_state(s);
  msocl_sim_destroy(s);
  return st;
}

static struct state run(const msocl_model *m, int held, int mode,
                        msocl_math math, float dt, int calls, int steps)
{
  return run_strained(m, held, mode, math, dt, calls, steps,
                      MSOCL_STRAIN_NONE);
}

static void assert_bitwise(const struct state *a, const struct state *b,
                           const char *what)
{
  const size_t bytes = 3 * (size_t)a->n * sizeof(float);
  ck_assert_int_eq(a->n, b->n);
  ck_assert_msg(memcmp(a->pos, b->pos, bytes) == 0 &&
                    memcmp(a->vel, b->vel, bytes) == 0,
                "%s: the tested layout differs from the held one: positions "
                "by %g, velocities by %g",
                what, scene_max_diff(a->pos, b->pos, 3 * a->n),
                scene_max_diff(a->vel, b->vel, 3 * a->n));
}

/* Sizes around a work-group's 64: narrower, a little wider (two groups a
 * row, the second mostly padding), and not square. */
static const int sizes[][2] = {{50, 37}, {70, 20}, {9, 64}};

START_TEST(busy_cloth_bitwise)
{
  msocl_model *m = busy_cloth(sizes[_i][0], sizes[_i][1]);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.5f;
  struct state bu = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 500);
  struct state gr = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 1, 500);
  struct state fu = run(m, 0, 2, MSOCL_MATH_PRECISE, dt, 1, 500);
  char what[64];
  snprintf(what, sizeof what, "%d x %d busy cloth", sizes[_i][0],
           sizes[_i][1]);
  assert_bitwise(&bu, &gr, what);
  snprintf(what, sizeof what, "%d x %d busy cloth, fused", sizes[_i][0],
           sizes[_i][1]);
  assert_bitwise(&bu, &fu, what);
  state_free(&fu);
  struct state vbu = run(m, 1, 3, MSOCL_MATH_PRECISE, dt, 1, 500);
  struct state vgr = run(m, 0, 3, MSOCL_MATH_PRECISE, dt, 1, 500);
  snprintf(what, sizeof what, "%d x %d busy cloth, Verlet", sizes[_i][0],
           sizes[_i][1]);
  assert_bitwise(&vbu, &vgr, what);
  state_free(&vbu);
  state_free(&vgr);
  struct state rbu = run(m, 1, 4, MSOCL_MATH_PRECISE, dt, 1, 300);
  struct state rgr = run(m, 0, 4, MSOCL_MATH_PRECISE, dt, 1, 300);
  snprintf(what, sizeof what, "%d x %d busy cloth, RK4", sizes[_i][0],
           sizes[_i][1]);
  assert_bitwise(&rbu, &rgr, what);
  state_free(&rbu);
  state_free(&rgr);
  /* and it moved: the test compares a motion, not a rest state */
  double far = 0.0;
  for (int i = 0; i < bu.n; i++)
    far = fmax(far, fabs(bu.vel[3 * i + 1]));
  ck_assert_msg(far > 0.01, "fastest vertical speed %g m/s", far);
  state_free(&bu);
  state_free(&gr);
  msocl_model_destroy(m);
}
END_TEST

/* The paper's scene, and a hanging cloth (pins, dashpots, no contact):
 * 500 steps on GRID in calls of 7 - the state kept in the planes between
 * calls - against one call on BUFFER. */
START_TEST(scenes_in_calls_bitwise)
{
  msocl_model *m = _i == 0 ? scene_tablecloth(33) : scene_hanging(24);
  float dt = scene_tablecloth_dt(_i == 0 ? 33 : 24);
  struct state bu = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 497);
  struct state gr = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 71, 7);
  struct state fu = run(m, 0, 2, MSOCL_MATH_PRECISE, dt, 71, 7);
  assert_bitwise(&bu, &gr, _i == 0 ? "tablecloth" : "hanging cloth");
  assert_bitwise(&bu, &fu, _i == 0 ? "tablecloth, fused" : "hanging, fused");
  state_free(&fu);
  /* Verlet carries its acceleration from call to call */
  struct state vbu = run(m, 1, 3, MSOCL_MATH_PRECISE, dt, 1, 497);
  struct state vgr = run(m, 0, 3, MSOCL_MATH_PRECISE, dt, 71, 7);
  assert_bitwise(&vbu, &vgr,
                 _i == 0 ? "tablecloth, Verlet" : "hanging, Verlet");
  state_free(&vbu);
  state_free(&vgr);
  struct state rbu = run(m, 1, 4, MSOCL_MATH_PRECISE, dt, 1, 203);
  struct state rgr = run(m, 0, 4, MSOCL_MATH_PRECISE, dt, 29, 7);
  assert_bitwise(&rbu, &rgr, _i == 0 ? "tablecloth, RK4" : "hanging, RK4");
  state_free(&rbu);
  state_free(&rgr);
  state_free(&bu);
  state_free(&gr);
  msocl_model_destroy(m);
}
END_TEST

/* Runs mode (make_strained's codes) in the held setup and in the tested
 * one, 3 calls of `steps` with strain limit `kind`, and asserts that both
 * end bit for bit alike (the label: scene, then what); returns the tested
 * run. */
static struct state held_vs_tested(const msocl_model *m, int mode, float dt,
                                   int steps, msocl_strain kind,
                                   const char *scene, const char *what)
{
  struct state a = run_strained(m, 1, mode, MSOCL_MATH_PRECISE, dt, 3,
                                steps, kind);
  struct state b = run_strained(m, 0, mode, MSOCL_MATH_PRECISE, dt, 3,
                                steps, kind);
  char label[96];
  snprintf(label, sizeof label, "%s, %s", scene, what);
  assert_bitwise(&a, &b, label);
  state_free(&a);
  return b;
}

/* Strain limiting (three sweeps a step, the default limit) on GRID is
 * bitwise BUFFER's: Provot's after every integrator, two passes and
 * fused, and the velocity kind between symplectic Euler's two passes
 * (with the table's contact on the tablecloth), on the paper's scene and
 * on a cloth hanging from two pinned corners (whose springs to a pinned
 * point move only the free end); and it changed the motion. */
START_TEST(strain_bitwise)
{
  msocl_model *m = _i ? scene_hanging(16) : scene_tablecloth(20);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.5f;
  struct state free_ = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 3, 67);
  static const int modes[5] = {1, 2, 3, 4, 1};
  static const char *const names[5] = {"Provot, two passes", "Provot, fused",
                                       "Provot, Verlet", "Provot, RK4",
                                       "velocity kind"};
  for (int q = 0; q < 5; q++) {
    const msocl_strain kind =
        q < 4 ? MSOCL_STRAIN_PROVOT : MSOCL_STRAIN_VELOCITY;
    /* the velocity kind, longer: into the drape, where its corrections
     * push points on the table into it (the response without friction) */
    const int steps = q < 4 ? 67 : 200;
    const char *scene = _i ? "hanging cloth" : "tablecloth";
    struct state gr = held_vs_tested(m, modes[q], dt, steps, kind, scene,
                                     names[q]);
    if (q == 0)
      ck_assert_msg(scene_max_diff(free_.pos, gr.pos, 3 * gr.n) > 1e-5,
                    "%s, %s: the strain limit changed nothing (%g m)", scene,
                    names[q], scene_max_diff(free_.pos, gr.pos, 3 * gr.n));
    state_free(&gr);
  }
  state_free(&free_);
  msocl_model_destroy(m);
}
END_TEST

/* Implicit Euler on GRID is bitwise BUFFER's: its dot products are summed
 * from the points' terms in groups of 64 whatever the layout (the 20-wide
 * tablecloth's rows, padded to 32, are not), on the tablecloth into its
 * contact and on the hanging cloth (pins, dashpots), at two and four times
 * the explicit stable step, unlimited and with each strain limit. */
START_TEST(implicit_bitwise)
{
  msocl_model *m = _i ? scene_hanging(16) : scene_tablecloth(20);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= _i ? 4.0f : 2.0f;
  static const msocl_strain kinds[3] = {
      MSOCL_STRAIN_NONE, MSOCL_STRAIN_PROVOT, MSOCL_STRAIN_VELOCITY};
  static const char *const names[3] = {"implicit Euler, unlimited",
                                       "implicit Euler, Provot",
                                       "implicit Euler, velocity kind"};
  for (int k = 0; k < 3; k++) {
    struct state gr = held_vs_tested(m, 5, dt, 40, kinds[k],
                                     _i ? "hanging cloth" : "tablecloth",
                                     names[k]);
    state_free(&gr);
  }
  msocl_model_destroy(m);
}
END_TEST

/* Explicit Euler on GRID is bitwise BUFFER's (at a tenth of the
 * symplectic step, where damping keeps it stable): its collisions are a
 * projection, unlike the other methods'; unlimited and with Provot's
 * correction. */
START_TEST(explicit_bitwise)
{
  msocl_model *m = _i ? scene_hanging(16) : scene_tablecloth(20);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.1f;
  for (int k = MSOCL_STRAIN_NONE; k <= MSOCL_STRAIN_PROVOT; k++) {
    struct state gr = held_vs_tested(
        m, 6, dt, 100, (msocl_strain)k, _i ? "hanging cloth" : "tablecloth",
        k ? "explicit Euler, Provot" : "explicit Euler, unlimited");
    state_free(&gr);
  }
  msocl_model_destroy(m);
}
END_TEST

/* A write between calls reaches the planes: GRID after a write is
 * bitwise BUFFER after the same write. */
START_TEST(writes_between_calls)
{
  msocl_model *m = scene_tablecloth(20);
  const float dt = scene_tablecloth_dt(20);
  /* symplectic Euler held and tested, then Verlet's (whose stored
   * acceleration a write must renew) */
  struct state out[4];
  for (int q = 0; q < 4; q++) {
    msocl_sim *s = make(m, q % 2 == 0, q < 2 ? 1 : 3, MSOCL_MATH_PRECISE, dt);
    ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
    struct state mid = read_state(s);
    for (int i = 0; i < mid.n; i++) {
      mid.pos[3 * i + 1] += 0.02f;   /* lift it */
      mid.vel[3 * i] = 0.1f;         /* and push it sideways */
    }
    ck_assert_int_eq(msocl_sim_write_positions(s, mid.pos), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_write_velocities(s, mid.vel), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_OK);
    out[q] = read_state(s);
    state_free(&mid);
    msocl_sim_destroy(s);
  }
  assert_bitwise(&out[0], &out[1], "written state");
  assert_bitwise(&out[2], &out[3], "written state, Verlet");
  for (int q = 0; q < 4; q++)
    state_free(&out[q]);
  msocl_model_destroy(m);
}
END_TEST

/* The state stays in the planes between calls: everything that looks at
 * it between one-step calls - the energy, the normals, a write of only
 * the velocities or only the positions (the other half comes from the
 * planes), the blow-up check's saved state and its restore - sees and
 * leaves on GRID what it does on BUFFER, bit for bit. q: symplectic
 * Euler, Verlet, RK4. */
START_TEST(resident_between_calls)
{
  static const int modes[3] = {1, 3, 4};
  msocl_model *m = scene_tablecloth(20);
  const float dt = scene_tablecloth_dt(20);
  int n = 0;
  msocl_model_point_count(m, &n);
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  struct state out[2];
  msocl_energy e[2][2];
  float *nrm[2], *lift = malloc(bytes), *push = malloc(bytes);
  msocl_model_get_positions(m, lift);
  for (int i = 0; i < n; i++) {
    lift[3 * i + 1] += 0.03f;
    push[3 * i] = 0.1f;
    push[3 * i + 1] = push[3 * i + 2] = 0.0f;
  }
  for (int k = 0; k < 2; k++) {
    msocl_sim *s = make(m, k == 0, modes[_i], MSOCL_MATH_PRECISE, dt);
    for (int c = 0; c < 5; c++)
      ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_energy(s, &e[k][0]), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 3), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_write_velocities(s, push), MSOCL_OK);
    for (int c = 0; c < 4; c++)
      ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
    nrm[k] = malloc(bytes);
    ck_assert_int_eq(msocl_sim_read_normals(s, nrm[k]), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 2), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_write_positions(s, lift), MSOCL_OK);
    /* across a blow-up check (check_every 100): one-step calls to 150 */
    for (int c = 0; c < 140; c++)
      ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_energy(s, &e[k][1]), MSOCL_OK);
    out[k] = read_state(s);
    msocl_sim_destroy(s);
  }
  assert_bitwise(&out[0], &out[1], "resident planes");
  ck_assert_msg(e[0][0].total == e[1][0].total &&
                    e[0][1].total == e[1][1].total,
                "energy: BUFFER %.17g, %.17g; GRID %.17g, %.17g",
                e[0][0].total, e[0][1].total, e[1][0].total, e[1][1].total);
  ck_assert(memcmp(nrm[0], nrm[1], bytes) == 0);
  for (int k = 0; k < 2; k++) {
    state_free(&out[k]);
    free(nrm[k]);
  }
  free(lift);
  free(push);
  msocl_model_destroy(m);
}
END_TEST

/* A blow-up restores the state saved at the last check: the planes must
 * start again from it, on GRID as on BUFFER. At 3x the stable step the
 * cloth blows up before the check at step 100, which restores step 0. */
START_TEST(restore_in_planes)
{
  msocl_model *m = scene_tablecloth(16);
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  struct state out[2];
  for (int k = 0; k < 2; k++) {
    msocl_sim *s = make(m, k == 0, 1, MSOCL_MATH_PRECISE, 3.0f * limit);
    int rc = MSOCL_OK, c = 0;
    for (; c < 100 && rc == MSOCL_OK; c++)
      rc = msocl_sim_step(s, 1);
    ck_assert_msg(rc == MSOCL_ERR_UNSTABLE && c == 100, "call %d: %s", c,
                  msocl_last_error());
    for (c = 0; c < 3; c++) /* on from the restored state */
      ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
    out[k] = read_state(s);
    msocl_sim_destroy(s);
  }
  assert_bitwise(&out[0], &out[1], "after a restore");
  state_free(&out[0]);
  state_free(&out[1]);
  msocl_model_destroy(m);
}
END_TEST

/* Relaxed math compiles its own arithmetic, so GRID and BUFFER may round
 * differently: they must still agree closely. */
START_TEST(relaxed_close)
{
  msocl_model *m = scene_tablecloth(32);
  const float dt = scene_tablecloth_dt(32);
  struct state bu = run(m, 1, 1, MSOCL_MATH_RELAXED, dt, 1, 300);
  struct state gr = run(m, 0, 1, MSOCL_MATH_RELAXED, dt, 1, 300);
  double d = scene_max_diff(bu.pos, gr.pos, 3 * bu.n);
  printf("relaxed math, GRID vs BUFFER after 300 steps: %g m\n", d);
  ck_assert_msg(d < 1e-4, "relaxed GRID differs from BUFFER by %g m", d);
  state_free(&bu);
  state_free(&gr);
  msocl_model_destroy(m);
}
END_TEST

/* The layout a sim of m under o took; fails the test if it was refused. */
static msocl_layout layout_of(const msocl_model *m, const msocl_sim_options *o)
{
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  msocl_layout kind = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_layout(s, &kind), MSOCL_OK);
  msocl_sim_destroy(s);
  return kind;
}

/* AUTO takes GRID for an intact cloth grid or lattice, whatever the
 * integrator and strain limit, and BUFFER for anything else (a mesh, a
 * grid with a spring added); EDGES runs where asked; forcing GRID where
 * it cannot run is a clear error. */
START_TEST(auto_and_errors)
{
  msocl_model *m = scene_tablecloth(16);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = scene_tablecloth_dt(16);
  ck_assert_int_eq(layout_of(m, &o), MSOCL_LAYOUT_GRID);
  for (int in = MSOCL_EXPLICIT_EULER; in <= MSOCL_IMPLICIT_EULER; in++) {
    o.integrator = (msocl_integrator)in;
    ck_assert_int_eq(layout_of(m, &o), MSOCL_LAYOUT_GRID);
  }
  o.integrator = MSOCL_SYMPLECTIC_EULER; /* and with either strain limit */
  for (int k = MSOCL_STRAIN_PROVOT; k <= MSOCL_STRAIN_VELOCITY; k++) {
    o.strain = (msocl_strain)k;
    ck_assert_int_eq(layout_of(m, &o), MSOCL_LAYOUT_GRID);
  }
  o.strain = MSOCL_STRAIN_NONE;
  /* EDGES where asked (AUTO never takes it) */
  o.tuning.layout = MSOCL_LAYOUT_EDGES;
  ck_assert_int_eq(layout_of(m, &o), MSOCL_LAYOUT_EDGES);
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  /* a lattice is a grid too */
  msocl_lattice_desc ld;
  msocl_lattice_desc_init(&ld);
  ld.nx = 6;
  ld.ny = 5;
  ld.nz = 4;
  msocl_model *lat = NULL;
  ck_assert_int_eq(msocl_model_lattice(&lat, &ld), MSOCL_OK);
  ck_assert_int_eq(layout_of(lat, &o), MSOCL_LAYOUT_GRID);
  msocl_model_destroy(lat);
  /* a spring across the cloth: no longer the grid GRID computes */
  const int ij[2] = {0, 16 * 16 - 1};
  const float k = 1.0f, rest = -1.0f;
  ck_assert_int_eq(msocl_model_add_springs(m, 1, ij, &k, &rest, NULL),
                   MSOCL_OK);
  ck_assert_int_eq(layout_of(m, &o), MSOCL_LAYOUT_BUFFER);
  msocl_model *sheet = obj_sheet(12, 10);
  ck_assert_int_eq(layout_of(sheet, &o), MSOCL_LAYOUT_BUFFER);
  /* GRID forced on either: refused, with the way out named */
  msocl_sim *s = NULL;
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_msg(strstr(msocl_last_error(), "BUFFER"), "unclear error: %s",
                msocl_last_error());
  ck_assert_int_eq(msocl_sim_create(&s, rt, sheet, &o), MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_null(s);
  msocl_model_destroy(sheet);
  msocl_model_destroy(m);
}
END_TEST

static const char *const inames[] = {"symplectic Euler", "explicit Euler",
                                     "Verlet", "RK4", "implicit Euler"};

/* `steps` steps (in two calls, the state read between) of m on `parts`
 * CPU devices of `two`. */
static void split_run(msocl_runtime *two, const msocl_model *m,
                      const msocl_sim_options *o, int parts, int steps,
                      float *pos, float *vel)
{
  msocl_sim_options q = *o;
  q.tuning.ndevices = parts;
  /* three: ranges that end inside rows, the middle one narrower than the
   * halo (implicit Euler: whole work-groups of 64) */
  const float w[3] = {1.0f, 0.3f, 1.0f};
  for (int d = 0; parts == 3 && o->integrator != MSOCL_IMPLICIT_EULER &&
                  d < 3; d++)
    q.tuning.weights[d] = w[d];
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, two, m, &q);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  msocl_layout kind = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_layout(s, &kind), MSOCL_OK);
  ck_assert_int_eq(kind, o->tuning.layout);
  for (int half = 0; half < 2; half++) {
    rc = msocl_sim_step(s, steps / 2);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    ck_assert_int_eq(msocl_sim_read_positions(s, pos), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_read_velocities(s, vel), MSOCL_OK);
  }
  msocl_sim_destroy(s);
}

/* A split, the halos exchanged plane by plane, is bitwise one device, for
 * every integrator on GRID, BUFFER and IMAGE2D, with colliders, pins and
 * dashpots (so velocities cross too), without boundary first and with it
 * (tuning.overlap AUTO and ON: each phase span by span, rows whole);
 * strain limiting stays refused on a split. Over 2 and (where there are)
 * 3 CPU devices (POCL_DEVICES="pthread pthread pthread"). _i: integrator
 * * 3 + layout. */
START_TEST(split_bitwise)
{
  char spec[64];
  const int ndev = scene_cpu_spec(spec, sizeof spec, 3);
  if (ndev < 2) {
    printf("split_bitwise: one CPU device only, not run\n");
    return;
  }
  const msocl_integrator in = (msocl_integrator)(_i / 3);
  const msocl_layout lays[3] = {MSOCL_LAYOUT_GRID, MSOCL_LAYOUT_BUFFER,
                                MSOCL_LAYOUT_IMAGE2D};
  const char *const lnames[3] = {"GRID", "BUFFER", "IMAGE2D"};
  const msocl_layout lay = lays[_i % 3];
  msocl_runtime *two = NULL;
  ck_assert_int_eq(msocl_runtime_create(&two, spec), MSOCL_OK);
  msocl_model *m = busy_cloth(16, 16); /* 256 points: 2 x 2 groups of 64 */
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = in == MSOCL_EXPLICIT_EULER ? 1e-4f : 1e-3f;
  o.integrator = in;
  o.tuning.layout = lay;
  o.check_every = 0;
  o.tuning.overlap = MSOCL_OFF;
  const size_t bytes = 3 * 256 * sizeof(float);
  float *p1 = malloc(bytes), *v1 = malloc(bytes), *p2 = malloc(bytes),
        *v2 = malloc(bytes), *p0 = malloc(bytes);
  msocl_model_get_positions(m, p0);
  split_run(two, m, &o, 1, 200, p1, v1);
  ck_assert_msg(scene_max_diff(p0, p1, 3 * 256) > 1e-4, "did not move");
  const msocl_choice overlaps[3] = {MSOCL_OFF, MSOCL_AUTO, MSOCL_ON};
  for (int q = 0; q < 3; q++)
    for (int parts = 2; parts <= ndev; parts++) {
      o.tuning.overlap = overlaps[q];
      split_run(two, m, &o, parts, 200, p2, v2);
      ck_assert_msg(memcmp(p1, p2, bytes) == 0 && memcmp(v1, v2, bytes) == 0,
                    "%s, %s, split over %d, overlap %d: positions differ "
                    "by %g, velocities by %g",
                    inames[in], lnames[_i % 3], parts, (int)overlaps[q],
                    scene_max_diff(p1, p2, 3 * 256),
                    scene_max_diff(v1, v2, 3 * 256));
    }
  o.tuning.ndevices = 2;
  msocl_sim *s = NULL;
  o.tuning.overlap = MSOCL_AUTO;
  o.strain = MSOCL_STRAIN_PROVOT;
  ck_assert_int_eq(msocl_sim_create(&s, two, m, &o), MSOCL_ERR_BAD_VALUE);
  free(p1); free(v1); free(p2); free(v2); free(p0);
  msocl_model_destroy(m);
  msocl_runtime_destroy(two);
}
END_TEST

/* A 2 x 2 x n lattice pads to 12 x 6 x (n + 4) points a plane: AUTO
 * takes BUFFER for it (memory in proportion to its points), forced GRID
 * still runs; one whose planes pass 2^31 floats is refused when GRID is
 * forced, before any allocation (a model with only its grid record: no
 * arrays to allocate from), and AUTO takes BUFFER for it. */
START_TEST(skinny_lattice)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = d.ny = 2;
  d.nz = 20000;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1e-4f;
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  const size_t plane = (size_t)12 * 6 * (20000 + 4);
  ck_assert_uint_eq(msocl__planes_bytes(m, &o), plane * 14 * sizeof(float));
  o.integrator = MSOCL_RK4;
  o.strain = MSOCL_STRAIN_PROVOT;
  ck_assert_uint_eq(msocl__planes_bytes(m, &o),
                    plane * (14 + 18 + 6) * sizeof(float));
  o.integrator = MSOCL_SYMPLECTIC_EULER;
  o.strain = MSOCL_STRAIN_NONE;
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  msocl_sim *s = NULL;
  msocl_layout kind = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_layout(s, &kind), MSOCL_OK);
  ck_assert_msg(kind == MSOCL_LAYOUT_BUFFER,
                "auto took layout %d, GRID's planes of %zu bytes for %d "
                "points", (int)kind, msocl__planes_bytes(m, &o), 4 * 20000);
  ck_assert_int_eq(msocl_sim_step(s, 2), MSOCL_OK);
  msocl_sim_destroy(s);
  o.tuning.layout = MSOCL_LAYOUT_GRID;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_layout(s, &kind), MSOCL_OK);
  ck_assert_int_eq(kind, MSOCL_LAYOUT_GRID);
  ck_assert_int_eq(msocl_sim_step(s, 2), MSOCL_OK);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);

  static msocl_model big; /* the grid record is all the checks read */
  big.grid.nx = big.grid.ny = 2;
  big.grid.nz = 40000000;
  big.n = 2 * 2 * big.grid.nz;
  ck_assert_int_eq(msocl__planes_refused(&o, &big, 0, big.n),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_msg(strstr(msocl_last_error(), "2^31") &&
                    strstr(msocl_last_error(), "2 x 2 x 40000000"),
                "unclear error: %s", msocl_last_error());
  o.tuning.layout = MSOCL_LAYOUT_AUTO;
  ck_assert_int_eq(msocl__planes_refused(&o, &big, 0, big.n), MSOCL_OK);
  ck_assert_int_eq(msocl__planes_would(&o, &big, 0, big.n), 0);
  ck_assert_int_eq(msocl__layout_auto(&rt->dev[0].info, &big,
                                      msocl__planes_would(&o, &big, 0, big.n)),
                   MSOCL_LAYOUT_BUFFER);
}
END_TEST

/* An irregular sheet as OBJ text: nx x ny points, jittered, each quad cut
 * along a diagonal a hash picks (so a point has 3 to 8 edges, and bending
 * springs across them), held 5 cm over a ball and a floor, one corner
 * pinned, with dashpots. */
static msocl_model *obj_sheet(int nx, int ny)
{
  size_t cap = 64 * (size_t)(nx * ny) * 4, len = 0;
  char *text = malloc(cap);
  ck_assert_ptr_nonnull(text);
  unsigned h = 12345u;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      h = h * 1103515245u + 12345u;
      const float jx = (float)((h >> 8) % 1000) * 2e-5f;
      h = h * 1103515245u + 12345u;
      const float jz = (float)((h >> 8) % 1000) * 2e-5f;
      len += (size_t)snprintf(text + len, cap - len, "v %.6f 0.05 %.6f\n",
                              -0.4f + 0.8f * (float)i / (float)(nx - 1) + jx,
                              -0.4f + 0.8f * (float)j / (float)(ny - 1) + jz);
    }
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      const int a = j * nx + i + 1, b = a + 1, c = a + nx, d = c + 1;
      h = h * 1103515245u + 12345u;
      if ((h >> 16) & 1)
        len += (size_t)snprintf(text + len, cap - len, "f %d %d %d\nf %d %d %d\n",
                                a, b, d, a, d, c);
      else
        len += (size_t)snprintf(text + len, cap - len, "f %d %d %d\nf %d %d %d\n",
                                a, b, c, b, d, c);
    }
  ck_assert_uint_lt(len, cap);
  msocl_obj_desc od;
  msocl_obj_desc_init(&od);
  od.k_edge = 40.0f;
  od.k_bend = 5.0f;
  od.damping = 2e-3f;
  msocl_model *m = NULL;
  int rc = msocl_model_from_obj_text(&m, text, len, &od);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  free(text);
  const float ball[3] = {0.1f, -0.1f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_sphere(m, ball, 0.14f, 0.4f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_plane(m, up, -0.05f, 0.3f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.999f), MSOCL_OK);
  return m;
}

/* A 6 x 5 x 4 lattice just over a floor, its corner in a ball, one top
 * corner pinned, viscous damping; `slim`: structural and body shear
 * springs only (14 a point, within IMAGE2D's 16), else the default sets
 * (24). */
static msocl_model *busy_lattice(int slim)
{
  msocl_lattice_desc d;
  msocl_lattice_desc_init(&d);
  d.nx = 6;
  d.ny = 5;
  d.nz = 4;
  if (slim) {
    d.k_shear_face = d.k_bend = 0.0f;
    d.k_shear_body = 80.0f;
  }
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_lattice(&m, &d), MSOCL_OK);
  const float up[3] = {0.0f, 1.0f, 0.0f}, ball[3] = {-0.07f, 0.09f, -0.07f};
  ck_assert_int_eq(msocl_model_add_plane(m, up, 0.099f, 0.3f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_add_sphere(m, ball, 0.025f, 0.2f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, 6 * 5 * 4 - 1, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 1e-4f), MSOCL_OK);
  return m;
}

/* The soft ball at subdivision 1 (42 surface points and a centre with 42
 * springs) over a floor. */
static msocl_model *small_ball(void)
{
  msocl_solid_desc d;
  msocl_solid_desc_init(&d);
  d.subdivisions = 1;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_solid(&m, &d), MSOCL_OK);
  const float up[3] = {0.0f, 1.0f, 0.0f};
  ck_assert_int_eq(msocl_model_add_plane(m, up, 0.0f, 0.3f), MSOCL_OK);
  return m;
}

/* Every integrator and strain limit: mode (make_strained's codes),
 * strain limit. */
static const struct {
  int mode;
  msocl_strain strain;
  const char *what;
} methods[] = {
    {1, MSOCL_STRAIN_NONE, "symplectic Euler"},
    {1, MSOCL_STRAIN_PROVOT, "symplectic Euler, Provot"},
    {1, MSOCL_STRAIN_VELOCITY, "symplectic Euler, velocity kind"},
    {2, MSOCL_STRAIN_NONE, "fused"},
    {2, MSOCL_STRAIN_PROVOT, "fused, Provot"},
    {3, MSOCL_STRAIN_NONE, "Verlet"},
    {3, MSOCL_STRAIN_PROVOT, "Verlet, Provot"},
    {4, MSOCL_STRAIN_NONE, "RK4"},
    {4, MSOCL_STRAIN_PROVOT, "RK4, Provot"},
    {5, MSOCL_STRAIN_NONE, "implicit Euler"},
    {5, MSOCL_STRAIN_PROVOT, "implicit Euler, Provot"},
    {5, MSOCL_STRAIN_VELOCITY, "implicit Euler, velocity kind"},
    {6, MSOCL_STRAIN_NONE, "explicit Euler"},
    {6, MSOCL_STRAIN_PROVOT, "explicit Euler, Provot"},
};

/* Mesh case _i: scene (cloth, lattice, OBJ sheet, ball's wide table,
 * ball spilling; the cloth, sheet and spill also with spring classes)
 * and layout; each held to held_setup's. */
static const struct {
  int scene;
  msocl_layout layout;
  int classes;
} meshes[] = {
    {0, MSOCL_LAYOUT_BUFFER, 0},  {0, MSOCL_LAYOUT_BUFFER, 1},
    {0, MSOCL_LAYOUT_IMAGE2D, 0}, {1, MSOCL_LAYOUT_BUFFER, 0},
    {1, MSOCL_LAYOUT_IMAGE2D, 0}, {2, MSOCL_LAYOUT_BUFFER, 0},
    {2, MSOCL_LAYOUT_BUFFER, 1},  {2, MSOCL_LAYOUT_IMAGE2D, 0},
    {3, MSOCL_LAYOUT_BUFFER, 0},  {4, MSOCL_LAYOUT_BUFFER, 0},
    {4, MSOCL_LAYOUT_BUFFER, 1},
};

static void setup_name(struct setup t, char *out, size_t cap)
{
  const int image = t.layout == MSOCL_LAYOUT_IMAGE2D;
  char slots[24] = "";
  if (!image && t.slots > 0)
    snprintf(slots, sizeof slots, ", %d slots", t.slots);
  snprintf(out, cap, "%s%s%s", image ? "IMAGE2D" : "BUFFER", slots,
           !image && t.classes == 1 ? " with classes" : "");
}

/* label: scene, tested setup against held setup. */
static msocl_model *mesh_scene(int q, char *label, size_t cap)
{
  static const char *const scenes[5] = {"cloth", "lattice", "OBJ sheet",
                                        "ball", "ball"};
  const int sc = meshes[q].scene;
  const int image = meshes[q].layout == MSOCL_LAYOUT_IMAGE2D;
  msocl_model *m = sc == 0   ? busy_cloth(20, 17)
                   : sc == 1 ? busy_lattice(image)
                   : sc == 2 ? obj_sheet(18, 15)
                             : small_ball();
  setup_.layout = meshes[q].layout;
  setup_.classes = meshes[q].classes;
  /* the ball's hub in the table, or past a table of 8 slots */
  setup_.slots = sc == 3 ? 48 : sc == 4 ? 8 : 0;
  char tested[48], held[48];
  setup_name(setup_, tested, sizeof tested);
  setup_name(held_setup(m, setup_), held, sizeof held);
  snprintf(label, cap, "%s, %s against %s", scenes[sc], tested, held);
  return m;
}

static void mesh_done(msocl_model *m)
{
  setup_ = (struct setup){MSOCL_LAYOUT_GRID, -1, 0, 0};
  msocl_model_destroy(m);
}

/* BUFFER and IMAGE2D are bitwise their held setups, for every integrator
 * and strain limit, in three calls (the state kept in the planes between
 * them); and the motion was not nothing. */
START_TEST(meshes_bitwise)
{
  char label[128];
  msocl_model *m = mesh_scene(_i, label, sizeof label);
  int degree = 0;
  msocl_model_max_degree(m, &degree);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  for (size_t q = 0; q < sizeof methods / sizeof methods[0]; q++) {
    const int in = methods[q].mode;
    const float h = in == 5 ? 2.0f * dt : in == 6 ? 0.1f * dt : 0.5f * dt;
    struct state st = held_vs_tested(m, in, h, 20, methods[q].strain, label,
                                     methods[q].what);
    if (q == 0) {
      double far = 0.0;
      for (int i = 0; i < st.n; i++)
        far = fmax(far, fabs(st.vel[3 * i + 1]));
      ck_assert_msg(far > 1e-3, "%s: fastest vertical speed %g m/s", label,
                    far);
    }
    state_free(&st);
  }
  printf("%s (degree %d): bitwise for %zu methods\n", label, degree,
         sizeof methods / sizeof methods[0]);
  mesh_done(m);
}
END_TEST

/* Writes between calls reach BUFFER's and IMAGE2D's planes, as GRID's
 * (writes_between_calls): symplectic Euler and Verlet, each bitwise its
 * held setup after the same writes. */
START_TEST(mesh_writes_between_calls)
{
  char label[128];
  msocl_model *m = mesh_scene(_i == 0 ? 5 : 7, label, sizeof label);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.5f;
  struct state out[4];
  for (int q = 0; q < 4; q++) {
    msocl_sim *s = make(m, q % 2 == 0, q < 2 ? 1 : 3, MSOCL_MATH_PRECISE, dt);
    ck_assert_int_eq(msocl_sim_step(s, 30), MSOCL_OK);
    struct state mid = read_state(s);
    for (int i = 0; i < mid.n; i++) {
      mid.pos[3 * i + 1] += 0.02f;
      mid.vel[3 * i] = 0.1f;
    }
    ck_assert_int_eq(msocl_sim_write_positions(s, mid.pos), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 7), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_write_velocities(s, mid.vel), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_step(s, 30), MSOCL_OK);
    out[q] = read_state(s);
    state_free(&mid);
    msocl_sim_destroy(s);
  }
  assert_bitwise(&out[0], &out[1], label);
  assert_bitwise(&out[2], &out[3], label);
  for (int q = 0; q < 4; q++)
    state_free(&out[q]);
  mesh_done(m);
}
END_TEST

/* A mesh gets BUFFER from AUTO, and runs on it as on forced BUFFER and
 * IMAGE2D. */
START_TEST(auto_meshes)
{
  msocl_model *m = obj_sheet(12, 10);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  const msocl_layout kinds[3] = {MSOCL_LAYOUT_AUTO, MSOCL_LAYOUT_BUFFER,
                                 MSOCL_LAYOUT_IMAGE2D};
  for (int q = 0; q < 3; q++) {
    o.tuning.layout = kinds[q];
    msocl_sim *s = NULL;
    msocl_layout kind = MSOCL_LAYOUT_AUTO;
    ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_layout(s, &kind), MSOCL_OK);
    ck_assert_int_eq(kind, q == 0 ? MSOCL_LAYOUT_BUFFER : kinds[q]);
    int rc = msocl_sim_step(s, 5);
    ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
    msocl_sim_destroy(s);
  }
  msocl_model_destroy(m);
}
END_TEST

/* The one-sweep symplectic Euler (lib/engine/planes_rows.c: rows of at
 * least 16 points) is bitwise BUFFER's, two passes or fused: rows a
 * vector wide, one more, two rows (the least a cloth has), three, many
 * rows a work-item; each collider kind alone, all three, none; pins at
 * corners and along the edges; dashpots on every other case; and a grid
 * narrower than a vector, which the planes passes run. colliders: 1
 * table, 2 sphere, 4 plane; pins: 1 two corners, 2 also edge
 * midpoints; 8 a capsule, 16 a turned box (the sweep's vector gaps,
 * bitwise the passes' scalar ones). Calls of many steps run up to four
 * a launch (blocks that recompute their neighbours' rows), bitwise calls
 * of one step. */
static const struct {
  int nx, ny, colliders, pins;
} rows_cases[] = {{16, 16, 1, 0}, {17, 9, 7, 2},   {47, 3, 4, 1},
                  {33, 2, 2, 1},  {40, 23, 0, 2},  {70, 37, 1, 1},
                  {12, 20, 7, 1}, {32, 24, 8, 0},  {21, 29, 16, 1},
                  {48, 17, 26, 2}};

static msocl_model *rows_cloth(int q)
{
  const int nx = rows_cases[q].nx, ny = rows_cases[q].ny;
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = nx;
  d.ny = ny;
  d.origin[0] = -0.5f;
  d.origin[1] = 0.05f;
  d.origin[2] = -0.5f;
  d.u[0] = 0.0f; d.u[1] = 0.0f; d.u[2] = 1.0f;
  d.v[0] = 1.0f; d.v[1] = 0.0f; d.v[2] = 0.0f;
  d.point_mass = 0.5f / (float)(nx * ny);
  d.k_stretch = 50.0f;
  d.k_shear = 10.0f;
  d.k_bend = 10.0f;
  d.damping = q % 2 ? 2e-3f : 0.0f;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  const float top[3] = {-0.1f, 0.0f, 0.0f}, ball[3] = {0.35f, -0.05f, 0.1f};
  const float up[3] = {0.0f, 1.0f, 0.0f};
  const int c = rows_cases[q].colliders;
  if (c & 1)
    ck_assert_int_eq(msocl_model_add_table(m, top, 0.3f, 0.3f), MSOCL_OK);
  if (c & 2)
    ck_assert_int_eq(msocl_model_add_sphere(m, ball, 0.15f, 0.5f), MSOCL_OK);
  if (c & 4)
    ck_assert_int_eq(msocl_model_add_plane(m, up, -0.2f, 0.2f), MSOCL_OK);
  const float ca[3] = {-0.35f, -0.06f, -0.2f}, cb[3] = {0.3f, -0.08f, 0.25f};
  if (c & 8)
    ck_assert_int_eq(msocl_model_add_capsule(m, ca, cb, 0.06f, 0.4f),
                     MSOCL_OK);
  /* 0.6 rad about y, then tilted: a unit quaternion (x, y, z, w) */
  const float turn[4] = {0.1f, 0.29f, -0.05f, 0.9513f},
              at[3] = {-0.1f, -0.12f, -0.2f}, half[3] = {0.15f, 0.05f, 0.1f};
  if (c & 16)
    ck_assert_int_eq(msocl_model_add_box(m, at, turn, half, 0.3f), MSOCL_OK);
  if (rows_cases[q].pins) {
    ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
    ck_assert_int_eq(msocl_model_pin(m, nx * ny - 1, 1), MSOCL_OK);
  }
  if (rows_cases[q].pins == 2) {
    const int edge[4] = {nx / 2, (ny / 2) * nx, (ny / 2) * nx + nx - 1,
                         (ny - 1) * nx + nx / 2};
    for (int e = 0; e < 4; e++)
      ck_assert_int_eq(msocl_model_pin(m, edge[e], 1), MSOCL_OK);
  }
  ck_assert_int_eq(msocl_model_set_viscous_damping(m, 1e-4f), MSOCL_OK);
  ck_assert_int_eq(msocl_model_set_air_resistance(m, 0.999f), MSOCL_OK);
  return m;
}

START_TEST(rows_bitwise)
{
  msocl_model *m = rows_cloth(_i);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.5f;
  struct state bu = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 400);
  struct state gr = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 4, 100);
  struct state fu = run(m, 0, 2, MSOCL_MATH_PRECISE, dt, 57, 7);
  char what[96];
  snprintf(what, sizeof what,
           "%d x %d cloth, colliders %d, pins %d, dashpots %d",
           rows_cases[_i].nx, rows_cases[_i].ny, rows_cases[_i].colliders,
           rows_cases[_i].pins, _i % 2);
  assert_bitwise(&bu, &gr, what);
  struct state bub = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 399);
  assert_bitwise(&bub, &fu, what);
  /* calls of one step: one launch a step, where the calls above ran up
   * to four a launch */
  struct state one = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 400, 1);
  assert_bitwise(&one, &gr, what);
  state_free(&one);
  double far = 0.0;
  for (int i = 0; i < bu.n; i++)
    far = fmax(far, fabs(bu.vel[3 * i + 1]));
  ck_assert_msg(far > 0.01, "%s: fastest vertical speed %g m/s", what, far);
  state_free(&bu);
  state_free(&bub);
  state_free(&gr);
  state_free(&fu);
  msocl_model_destroy(m);
}
END_TEST

/* GRID's sweep gives the same bits at every count of steps a launch
 * (tuning.sweep_steps, 1 one launch a step), in one call that ends inside
 * a launch and in calls shorter than AUTO's trials; AUTO settles on one
 * of its candidates, and msocl_sim_sweep_steps says which. */
START_TEST(rows_steps_a_launch)
{
  msocl_model *m = rows_cloth(_i ? 5 : 1);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  dt *= 0.5f;
  setup_.sweep = 1;
  struct state one = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 1, 301);
  static const int forced[] = {2, 3, 5, MSOCL_MAX_SWEEP_STEPS};
  char what[64];
  for (int q = 0; q < 4; q++) {
    setup_.sweep = forced[q];
    msocl_sim *s = make(m, 0, 1, MSOCL_MATH_PRECISE, dt);
    int k = -1;
    ck_assert_int_eq(msocl_sim_sweep_steps(s, &k), MSOCL_OK);
    ck_assert_int_eq(k, forced[q]);
    ck_assert_int_eq(msocl_sim_step(s, 301), MSOCL_OK);
    struct state st = read_state(s);
    snprintf(what, sizeof what, "%d steps a launch", forced[q]);
    assert_bitwise(&one, &st, what);
    state_free(&st);
    msocl_sim_destroy(s);
  }
  /* AUTO: timing until its trials are done, in one long call or, where
   * calls are too short for a trial, after a few launches */
  setup_.sweep = 0;
  for (int calls = 1; calls <= 43; calls += 42) {
    msocl_sim *s = make(m, 0, 1, MSOCL_MATH_PRECISE, dt);
    int k = -1;
    ck_assert_int_eq(msocl_sim_sweep_steps(s, &k), MSOCL_OK);
    ck_assert_int_eq(k, 0);
    for (int c = 0; c < calls; c++)
      ck_assert_int_eq(msocl_sim_step(s, 301 / calls), MSOCL_OK);
    ck_assert_int_eq(msocl_sim_sweep_steps(s, &k), MSOCL_OK);
    ck_assert_msg(k >= 2 && k <= 4, "AUTO chose %d steps a launch", k);
    struct state st = read_state(s);
    snprintf(what, sizeof what, "AUTO in %d calls (%d steps a launch)",
             calls, k);
    assert_bitwise(&one, &st, what);
    state_free(&st);
    msocl_sim_destroy(s);
  }
  /* out of range: refused; no sweep (BUFFER): a launch a step */
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  msocl_sim *s = NULL;
  for (int q = 0; q < 2; q++) {
    o.tuning.sweep_steps = q ? MSOCL_MAX_SWEEP_STEPS + 1 : -1;
    ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_ERR_BAD_VALUE);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(msocl_last_error(), "sweep_steps"));
  }
  o.tuning.sweep_steps = 3;
  o.tuning.layout = MSOCL_LAYOUT_BUFFER;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  int k = -1;
  ck_assert_int_eq(msocl_sim_sweep_steps(s, &k), MSOCL_OK);
  ck_assert_int_eq(k, 1);
  ck_assert_int_eq(msocl_sim_sweep_steps(NULL, &k), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_sim_sweep_steps(s, NULL), MSOCL_ERR_NULL_HANDLE);
  msocl_sim_destroy(s);
  setup_.sweep = 0;
  state_free(&one);
  msocl_model_destroy(m);
}
END_TEST

/* Dashpotted cloth in the sweep (the hanging cloth, 48 points a row) is
 * bitwise BUFFER's, and BUFFER in calls bitwise IMAGE2D in one, after
 * 200 symplectic steps that swing it. */
START_TEST(rows_dashpots_buffer)
{
  msocl_model *m = scene_hanging(48);
  const float dt = scene_tablecloth_dt(48);
  struct state g = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 4, 50);
  struct state b = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 200);
  setup_.layout = MSOCL_LAYOUT_BUFFER;
  struct state bp = run(m, 0, 1, MSOCL_MATH_PRECISE, dt, 2, 100);
  struct state im = run(m, 1, 1, MSOCL_MATH_PRECISE, dt, 1, 200);
  setup_.layout = MSOCL_LAYOUT_GRID;
  assert_bitwise(&b, &g, "hanging cloth, GRID's sweep against BUFFER");
  assert_bitwise(&im, &bp, "hanging cloth, BUFFER against IMAGE2D");
  double far = 0.0;
  for (int i = 0; i < g.n; i++)
    far = fmax(far, fabs(g.vel[3 * i + 1]));
  ck_assert_msg(far > 0.1, "fastest vertical speed %g m/s", far);
  state_free(&g);
  state_free(&b);
  state_free(&bp);
  state_free(&im);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  /* three PoCL CPU devices for the splits, unless the caller chose; before
   * the first OpenCL call */
  setenv("POCL_DEVICES", "pthread pthread pthread", 0);
  scene_require_device("check_planes");
  Suite *su = suite_create("planes");
  TCase *tc = tcase_create("planes");
  tcase_add_checked_fixture(tc, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_loop_test(tc, busy_cloth_bitwise, 0,
                      (int)(sizeof sizes / sizeof sizes[0]));
  tcase_add_loop_test(tc, scenes_in_calls_bitwise, 0, 2);
  tcase_add_test(tc, writes_between_calls);
  tcase_add_loop_test(tc, strain_bitwise, 0, 2);
  tcase_add_loop_test(tc, implicit_bitwise, 0, 2);
  tcase_add_loop_test(tc, explicit_bitwise, 0, 2);
  tcase_add_loop_test(tc, resident_between_calls, 0, 3);
  tcase_add_test(tc, restore_in_planes);
  tcase_add_test(tc, relaxed_close);
  tcase_add_test(tc, auto_and_errors);
  tcase_add_test(tc, skinny_lattice);
  tcase_add_loop_test(tc, meshes_bitwise, 0,
                      (int)(sizeof meshes / sizeof meshes[0]));
  tcase_add_loop_test(tc, mesh_writes_between_calls, 0, 2);
  tcase_add_test(tc, auto_meshes);
  suite_add_tcase(su, tc);
  TCase *split = tcase_create("split");
  tcase_add_checked_fixture(split, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(split, 300);
  tcase_add_loop_test(split, split_bitwise, 0, 15);
  suite_add_tcase(su, split);
  TCase *rows = tcase_create("rows");
  tcase_add_checked_fixture(rows, scene_setup_cpu, scene_teardown);
  tcase_set_timeout(rows, 300);
  tcase_add_loop_test(rows, rows_bitwise, 0,
                      (int)(sizeof rows_cases / sizeof rows_cases[0]));
  tcase_add_test(rows, rows_dashpots_buffer);
  tcase_add_loop_test(rows, rows_steps_a_launch, 0, 2);
  suite_add_tcase(su, rows);
  return scene_run(su);
}
