/* Stability where methods fail: the predicted step limit against the
 * blow-up detector on a chain and a cloth grid, energy behaviour over long
 * runs, and the rollback a user gets for an unstable step. */
#include "scenes.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static msocl_runtime *rt;
static const char *const names[] = {"symplectic Euler", "explicit Euler",
                                    "Verlet", "RK4", "implicit Euler"};

static void setup(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, "cpu"), MSOCL_OK);
}

static void teardown(void)
{
  msocl_runtime_destroy(rt);
  rt = NULL;
}

/* 20 masses of 10 g on springs of 10 N/m, 0.1 m apart along x, pinned at
 * one end; no gravity, no damping. */
static msocl_model *chain(void)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  float xyz[60] = {0}, mass[20], k[19];
  int ij[38];
  for (int i = 0; i < 20; i++) {
    xyz[3 * i] = 0.1f * (float)i;
    mass[i] = 0.01f;
  }
  for (int s = 0; s < 19; s++) {
    ij[2 * s] = s;
    ij[2 * s + 1] = s + 1;
    k[s] = 10.0f;
  }
  msocl_model_add_points(m, 20, xyz, mass, NULL);
  msocl_model_add_springs(m, 19, ij, k, NULL, NULL);
  msocl_model_pin(m, 0, 1);
  msocl_model_set_gravity(m, 0, 0, 0);
  return m;
}

/* The paper's 12 x 12 cloth grid (stretch, shear, bend), free, no
 * gravity, no damping. */
static msocl_model *grid(void)
{
  msocl_model *m = scene_tablecloth(12);
  msocl_model_set_gravity(m, 0, 0, 0);
  msocl_model_set_viscous_damping(m, 0.0f);
  return m;
}

/* Sim at dt with the state perturbed by +-1 mm (deterministic), so the
 * highest modes are excited from the start rather than by round-off. */
static msocl_sim *perturbed(const msocl_model *m, msocl_integrator in,
                            float dt)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = in;
  o.check_every = 50;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  int n;
  msocl_model_point_count(m, &n);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  msocl_model_get_positions(m, p);
  unsigned x = 12345u;
  for (int i = 3; i < 3 * n; i++) { /* point 0 of the chain is pinned */
    x = x * 1103515245u + 12345u;
    p[i] += 1e-3f * ((float)((x >> 8) & 0xffff) / 32768.0f - 1.0f);
  }
  ck_assert_int_eq(msocl_sim_write_positions(s, p), MSOCL_OK);
  free(p);
  return s;
}

/* 0.9 x the predicted limit runs 3000 steps; 1.2 x is caught as unstable
 * (the error code, with a finite rolled-back state). */
static void edges(msocl_model *m, const char *what, msocl_integrator in)
{
  float limit;
  ck_assert_int_eq(msocl_stable_dt(m, in, &limit), MSOCL_OK);
  msocl_sim *s = perturbed(m, in, 0.9f * limit);
  int rc = msocl_sim_step(s, 3000);
  ck_assert_msg(rc == MSOCL_OK, "%s, %s at 0.9 x %g: %s", what, names[in],
                limit, msocl_last_error());
  msocl_sim_destroy(s);
  s = perturbed(m, in, 1.2f * limit);
  rc = msocl_sim_step(s, 3000);
  printf("%s, %s: limit %.4g s; at 1.2x: %s\n", what, names[in], limit,
         rc == MSOCL_ERR_UNSTABLE ? msocl_last_error() : "no blow-up");
  ck_assert_int_eq(rc, MSOCL_ERR_UNSTABLE);
  int n;
  msocl_sim_point_count(s, &n);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  msocl_sim_read_positions(s, p);
  for (int i = 0; i < 3 * n; i++)
    ck_assert(isfinite(p[i]));
  free(p);
  msocl_sim_destroy(s);
}

static const msocl_integrator explicit_methods[3] = {
    MSOCL_SYMPLECTIC_EULER, MSOCL_VERLET, MSOCL_RK4};

START_TEST(chain_edges)
{
  msocl_model *m = chain();
  edges(m, "chain", explicit_methods[_i]);
  msocl_model_destroy(m);
}
END_TEST

START_TEST(grid_edges)
{
  msocl_model *m = grid();
  edges(m, "cloth grid", explicit_methods[_i]);
  msocl_model_destroy(m);
}
END_TEST

/* Backward Euler at 50 x the symplectic limit: no blow-up, and its
 * artificial damping takes energy out (never adds it). */
START_TEST(implicit_at_50x)
{
  msocl_model *m = grid();
  float limit;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit),
                   MSOCL_OK);
  float inf;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_IMPLICIT_EULER, &inf), MSOCL_OK);
  ck_assert(isinf(inf));
  msocl_sim *s = perturbed(m, MSOCL_IMPLICIT_EULER, 50.0f * limit);
  msocl_energy e0, e1;
  ck_assert_int_eq(msocl_sim_energy(s, &e0), MSOCL_OK);
  int rc = msocl_sim_step(s, 200);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_energy(s, &e1), MSOCL_OK);
  int it;
  double res;
  msocl_sim_solver_stats(s, &it, &res);
  printf("implicit Euler at 50x (dt %.3g s): energy %.3g -> %.3g J; CG %d "
         "iterations, residual %.2g\n",
         50.0 * limit, e0.total, e1.total, it, res);
  ck_assert(isfinite(e1.total));
  ck_assert_double_le(e1.total, e0.total);
  ck_assert_double_le(res, 1e-5);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A single undamped oscillator: mass 0.1 kg on 10 N/m from a pinned point,
 * no gravity, 0.1 m amplitude along the spring (so exactly linear). */
static msocl_model *oscillator(void)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  const float xyz[6] = {0, 0, 0, 1.1f, 0, 0}, mass[2] = {1.0f, 0.1f};
  const int ij[2] = {0, 1};
  const float k = 10.0f, rest = 1.0f;
  msocl_model_add_points(m, 2, xyz, mass, NULL);
  msocl_model_add_springs(m, 1, ij, &k, &rest, NULL);
  msocl_model_pin(m, 0, 1);
  msocl_model_set_gravity(m, 0, 0, 0);
  return m;
}

/* Worst |E - E0| / E0 over `steps`, sampled every 10 steps. */
static double energy_drift(msocl_integrator in, float dt, int steps)
{
  msocl_model *m = oscillator();
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = in;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_energy e0, e;
  msocl_sim_energy(s, &e0);
  double worst = 0.0;
  for (int k = 0; k < steps / 10; k++) {
    ck_assert_int_eq(msocl_sim_step(s, 10), MSOCL_OK);
    msocl_sim_energy(s, &e);
    double d = fabs(e.total - e0.total) / e0.total;
    worst = d > worst ? d : worst;
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  return worst;
}

/* Symplectic methods conserve a modified quadratic form Q instead of the
 * energy H, so H oscillates and never drifts. Starting at rest at full
 * amplitude, H / H0 stays within 1 + (h w / 2) / (1 - h w / 2) for
 * symplectic Euler (Q = v^2 + w^2 x^2 - h w^2 x v) and 1 + (h w)^2 / 4 for
 * Verlet; the stated bounds add 5% to these, over 10^4 steps. */
START_TEST(symplectic_energy_bounded)
{
  const double w = 10.0, hw = 0.1;
  double se = energy_drift(MSOCL_SYMPLECTIC_EULER, (float)(hw / w), 10000);
  double vv = energy_drift(MSOCL_VERLET, (float)(hw / w), 10000);
  printf("energy over 10^4 steps at h w = 0.1: symplectic Euler %.3g, "
         "Verlet %.3g (relative)\n", se, vv);
  ck_assert_double_le(se, 1.05 * (hw / 2) / (1 - hw / 2));
  ck_assert_double_le(vv, 1.05 * hw * hw / 4);
}
END_TEST

/* Forward Euler on x'' = -w^2 x multiplies w^2 x^2 + v^2, hence the
 * energy, by exactly 1 + (h w)^2 each step. */
START_TEST(explicit_euler_energy_growth)
{
  msocl_model *m = oscillator();
  const double w = 10.0, hw = 0.05;
  const int steps = 1000;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = (float)(hw / w);
  o.integrator = MSOCL_EXPLICIT_EULER;
  o.check_every = 0;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_energy e0, e;
  msocl_sim_energy(s, &e0);
  ck_assert_int_eq(msocl_sim_step(s, steps), MSOCL_OK);
  msocl_sim_energy(s, &e);
  double expect = pow(1.0 + hw * hw, steps);
  printf("explicit Euler: energy grew %.4f x in %d steps, theory %.4f x\n",
         e.total / e0.total, steps, expect);
  ck_assert_double_eq_tol(e.total / e0.total, expect, 0.01 * expect);
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_EXPLICIT_EULER, &dt),
                   MSOCL_ERR_UNSTABLE);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Forward Euler with a dashpot c on the oscillator's spring: the mode's
 * rate g = c/m against w^2 = k/m gives the limit h <= c/k exactly, the
 * amplitude squared changing by 1 - h g + h^2 w^2 a step: 0.9 of the limit
 * loses energy; at 1.2 it grows (by 6.8x over 20000 steps, theory). */
START_TEST(explicit_euler_dashpot_limit)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  const float xyz[6] = {0, 0, 0, 1.1f, 0, 0}, mass[2] = {1.0f, 0.1f};
  const int ij[2] = {0, 1};
  const float k = 10.0f, rest = 1.0f, c = 0.02f;
  msocl_model_add_points(m, 2, xyz, mass, NULL);
  msocl_model_add_springs(m, 1, ij, &k, &rest, &c);
  msocl_model_pin(m, 0, 1);
  msocl_model_set_gravity(m, 0, 0, 0);
  float limit;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_EXPLICIT_EULER, &limit), MSOCL_OK);
  ck_assert_float_eq_tol(limit, c / k, 1e-7f);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.integrator = MSOCL_EXPLICIT_EULER;
  o.dt = 0.9f * limit;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_energy e0, e1;
  msocl_sim_energy(s, &e0);
  ck_assert_int_eq(msocl_sim_step(s, 5000), MSOCL_OK);
  msocl_sim_energy(s, &e1);
  ck_assert_double_lt(e1.total, e0.total);
  msocl_sim_destroy(s);
  o.dt = 1.2f * limit;
  o.check_every = 0;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 20000), MSOCL_OK);
  msocl_sim_energy(s, &e1);
  double h = o.dt, g = c / 0.1, w2 = k / 0.1;
  double theory = pow(1.0 - h * g + h * h * w2, 20000);
  printf("explicit Euler with a dashpot at 1.2x its limit: energy %.3g x "
         "(theory %.3g x)\n", e1.total / e0.total, theory);
  ck_assert_double_gt(e1.total / e0.total, 2.0);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The Gershgorin bound against analytic values: a pinned chain's interior
 * row gives w^2 <= 4 k / m, an oscillator w^2 = k / m exactly. */
START_TEST(stable_dt_values)
{
  msocl_model *m = chain();
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, 2.0f / sqrtf(4.0f * 10.0f / 0.01f), 1e-6f);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_RK4, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, 2.0f * sqrtf(2.0f) / sqrtf(4.0f * 10.0f / 0.01f),
                         1e-6f);
  msocl_model_set_viscous_damping(m, 0.01f); /* rate c/m = 1/s */
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_EXPLICIT_EULER, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, 1.0f / 4000.0f, 1e-8f);
  ck_assert_int_eq(msocl_stable_dt(NULL, MSOCL_RK4, &dt),
                   MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_RK4, NULL), MSOCL_ERR_NULL_HANDLE);
  ck_assert_int_eq(msocl_stable_dt(m, (msocl_integrator)9, &dt),
                   MSOCL_ERR_BAD_VALUE);
  msocl_model_destroy(m);
  m = oscillator();
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_VERLET, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, 2.0f / 10.0f, 1e-6f);
  msocl_model_destroy(m);
}
END_TEST

/* The default cloth hanging from two corners (points 0 and 31), no
 * damping: it falls, swings and stretches its corner springs to twice
 * their rest length, where they stiffen sideways; msocl_stable_dt (the
 * rest state's limit) blows up within 200 steps at 0.9 x. */
static msocl_model *pinned_cloth(void)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, 31, 1);
  return m;
}

/* 0.9 x msocl_safe_dt holds the pinned cloth for 50 000 steps (the blow-up
 * check every 100), in the GRID layout (AUTO) and in BUFFER; the state it
 * reaches has a smaller stable_dt_at than the model at rest. */
START_TEST(pinned_cloth_safe_step)
{
  static const msocl_layout layouts[2] = {MSOCL_LAYOUT_AUTO,
                                          MSOCL_LAYOUT_BUFFER};
  msocl_model *m = pinned_cloth();
  float rest, safe, here;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &rest),
                   MSOCL_OK);
  ck_assert_int_eq(msocl_safe_dt(m, MSOCL_SYMPLECTIC_EULER, &safe),
                   MSOCL_OK);
  ck_assert_float_lt(safe, rest);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 0.9f * safe;
  o.tuning.layout = layouts[_i];
  o.check_every = 100;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  int rc = msocl_sim_step(s, 50000);
  ck_assert_msg(rc == MSOCL_OK, "0.9 x safe step %g s: %s", (double)safe,
                msocl_last_error());
  float *p = malloc(3 * 1024 * sizeof *p);
  ck_assert_int_eq(msocl_sim_read_positions(s, p), MSOCL_OK);
  ck_assert_int_eq(msocl_stable_dt_at(m, p, MSOCL_SYMPLECTIC_EULER, &here),
                   MSOCL_OK);
  printf("pinned cloth, layout %d: stable_dt %.4g s, safe_dt %.4g s, "
         "stable_dt_at after 50 000 steps %.4g s\n", (int)layouts[_i],
         rest, safe, here);
  ck_assert_float_lt(here, rest);
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Symplectic Euler on a mode damped at rate g is stable for
 * h^2 w^2 + 2 h g < 4, not for h w < 2 and h g < 2 apart: the oscillator
 * (w = 10 rad/s) with viscous damping g = 10/s has the limit
 * 4 / (g + sqrt(g^2 + 4 w^2)) = 0.1236 s, where each limit alone allows
 * 0.2 s. 0.9 x loses energy; 1.2 x is caught. */
START_TEST(stable_dt_damped)
{
  msocl_model *m = oscillator();
  msocl_model_set_viscous_damping(m, 1.0f); /* on the free 0.1 kg: 10/s */
  const double g = 10.0, w = 10.0, h = 4.0 / (g + sqrt(g * g + 4 * w * w));
  float dt;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, (float)h, 1e-5f);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_VERLET, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, (float)h, 1e-5f);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = (float)(0.9 * h);
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  msocl_energy e0, e1;
  msocl_sim_energy(s, &e0);
  ck_assert_int_eq(msocl_sim_step(s, 2000), MSOCL_OK);
  msocl_sim_energy(s, &e1);
  ck_assert_double_lt(e1.total, e0.total);
  msocl_sim_destroy(s);
  o.dt = (float)(1.2 * h);
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 2000), MSOCL_ERR_UNSTABLE);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* Nothing bounds the step of a model without springs (or damping): a clear
 * error, not +infinity. Two coincident points joined by a spring of
 * positive rest length have no linearisation: msocl_stable_dt refuses,
 * msocl_safe_dt (any state) still answers. */
START_TEST(stable_dt_refuses)
{
  msocl_model *m = NULL;
  msocl_model_create(&m);
  const float xyz[6] = {0, 0, 0, 0, 0, 0}, mass[2] = {0.1f, 0.1f};
  msocl_model_add_points(m, 2, xyz, mass, NULL);
  float dt = 1.0f;
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt),
                   MSOCL_ERR_BAD_COUNT);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "no spring"));
  ck_assert_float_eq(dt, 0.0f);
  ck_assert_int_eq(msocl_safe_dt(m, MSOCL_RK4, &dt), MSOCL_ERR_BAD_COUNT);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_IMPLICIT_EULER, &dt), MSOCL_OK);
  ck_assert(isinf(dt));
  msocl_model_set_viscous_damping(m, 0.1f); /* rate 1/s: h <= 2 s */
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  ck_assert_float_eq_tol(dt, 2.0f, 1e-6f);
  msocl_model_set_viscous_damping(m, 0.0f);
  const int ij[2] = {0, 1};
  const float k = 10.0f, rest = 0.1f;
  msocl_model_add_springs(m, 1, ij, &k, &rest, NULL);
  ck_assert_int_eq(msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &dt),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "coincide"));
  ck_assert_int_eq(msocl_stable_dt_at(m, xyz, MSOCL_VERLET, &dt),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_stable_dt_at(m, NULL, MSOCL_VERLET, &dt),
                   MSOCL_ERR_NULL_HANDLE);
  /* a state that is not one: refused as the writes refuse it */
  float bad[sizeof xyz / sizeof xyz[0]];
  memcpy(bad, xyz, sizeof xyz);
  bad[4] = INFINITY;
  ck_assert_int_eq(msocl_stable_dt_at(m, bad, MSOCL_VERLET, &dt),
                   MSOCL_ERR_NOT_FINITE);
  bad[4] = NAN;
  ck_assert_int_eq(msocl_stable_dt_at(m, bad, MSOCL_VERLET, &dt),
                   MSOCL_ERR_NOT_FINITE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "point 1: y = nan"));
  bad[4] = 1e19f;
  ck_assert_int_eq(msocl_stable_dt_at(m, bad, MSOCL_VERLET, &dt),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_int_eq(msocl_safe_dt(m, MSOCL_SYMPLECTIC_EULER, &dt), MSOCL_OK);
  ck_assert(isfinite(dt) && dt > 0.0f);
  msocl_model_destroy(m);
}
END_TEST

/* The grid at 3x its stable symplectic Euler step, perturbed: it blows
 * up before its first check (step 50). *m and *n: its model and points. */
static msocl_sim *unstable(msocl_model **m, int *n)
{
  *m = grid();
  float limit;
  msocl_stable_dt(*m, MSOCL_SYMPLECTIC_EULER, &limit);
  msocl_sim *s = perturbed(*m, MSOCL_SYMPLECTIC_EULER, 3.0f * limit);
  msocl_sim_point_count(s, n);
  return s;
}

/* A user who asks for an unstable step gets MSOCL_ERR_UNSTABLE naming the
 * steps, and the state of the last good check, bit for bit. */
START_TEST(unstable_rolls_back)
{
  msocl_model *m = NULL;
  int n;
  msocl_sim *s = unstable(&m, &n);
  float *before = malloc(3 * (size_t)n * sizeof *before),
        *after = malloc(3 * (size_t)n * sizeof *after),
        *vb = malloc(3 * (size_t)n * sizeof *vb),
        *va = malloc(3 * (size_t)n * sizeof *va);
  msocl_sim_read_positions(s, before);
  msocl_sim_read_velocities(s, vb);
  ck_assert_int_eq(msocl_sim_step(s, 1000), MSOCL_ERR_UNSTABLE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "blew up between steps 0 and 50"));
  msocl_sim_read_positions(s, after);
  msocl_sim_read_velocities(s, va);
  ck_assert(memcmp(before, after, 3 * (size_t)n * sizeof *after) == 0);
  ck_assert(memcmp(vb, va, 3 * (size_t)n * sizeof *va) == 0);
  long long steps;
  msocl_sim_step_count(s, &steps);
  ck_assert_int_eq(steps, 0);
  free(before); free(after); free(vb); free(va);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The check counts steps across calls: one step a call runs unchecked
 * until check_every steps are done, and the call that completes them
 * reports the blow-up and restores the state saved where they started. A
 * write does not start the count again. At 3x the stable step the state
 * is NaN within 20 steps; unchecked, the calls still return MSOCL_OK. */
START_TEST(check_counts_across_calls)
{
  msocl_model *m = NULL;
  int n;
  msocl_sim *s = unstable(&m, &n);
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  float *p0 = malloc(bytes), *v0 = malloc(bytes), *p = malloc(bytes),
        *v = malloc(bytes);
  msocl_sim_read_positions(s, p0);
  msocl_sim_read_velocities(s, v0);
  long long steps;
  /* 49 single steps unchecked; the 50th completes the stretch */
  for (int q = 0; q < 49; q++)
    ck_assert_msg(msocl_sim_step(s, 1) == MSOCL_OK, "call %d: %s", q,
                  msocl_last_error());
  ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_ERR_UNSTABLE);
  ck_assert_msg(strstr(msocl_last_error(), "blew up between steps 0 and 50"),
                "%s", msocl_last_error());
  msocl_sim_step_count(s, &steps);
  ck_assert_int_eq(steps, 0);
  msocl_sim_read_positions(s, p);
  ck_assert(memcmp(p, p0, bytes) == 0);
  /* 30 single steps, then the first state written back: the write finds
   * the state it replaces blown up, the count goes on, and the call that
   * completes step 50 reports it and restores step 0 */
  for (int q = 0; q < 30; q++)
    ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_write_positions(s, p0), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_write_velocities(s, v0), MSOCL_OK);
  for (int q = 0; q < 19; q++)
    ck_assert_msg(msocl_sim_step(s, 1) == MSOCL_OK, "call %d after the "
                  "write: %s", q, msocl_last_error());
  ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_ERR_UNSTABLE);
  ck_assert_msg(strstr(msocl_last_error(), "blew up between steps 0 and 30"),
                "%s", msocl_last_error());
  ck_assert_msg(strstr(msocl_last_error(), "where it was written"), "%s",
                msocl_last_error());
  msocl_sim_step_count(s, &steps);
  ck_assert_int_eq(steps, 0);
  msocl_sim_read_positions(s, p);
  msocl_sim_read_velocities(s, v);
  ck_assert(memcmp(p, p0, bytes) == 0 && memcmp(v, v0, bytes) == 0);
  /* 20 single steps, then a call of 70 checks at the stretch's end, in
   * its middle */
  for (int q = 0; q < 20; q++)
    ck_assert_int_eq(msocl_sim_step(s, 1), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 70), MSOCL_ERR_UNSTABLE);
  ck_assert_msg(strstr(msocl_last_error(), "blew up between steps 0 and 50"),
                "%s", msocl_last_error());
  msocl_sim_read_positions(s, p);
  ck_assert(memcmp(p, p0, bytes) == 0);
  free(p0); free(v0); free(p); free(v);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A scene whose energy is only round-off: the grid at rest without
 * gravity, free (kind 0), lying on a plane (1), or touching a sphere under
 * its point (6, 6) (2). */
static msocl_model *at_rest(int kind)
{
  msocl_model *m = grid();
  float xyz[3 * 144];
  msocl_model_get_positions(m, xyz);
  const float *p = xyz + 3 * (6 * 12 + 6), up[3] = {0.0f, 1.0f, 0.0f};
  const float centre[3] = {p[0], p[1] - 0.3f, p[2]};
  if (kind == 1)
    ck_assert_int_eq(msocl_model_add_plane(m, up, p[1], 0.3f), MSOCL_OK);
  if (kind == 2)
    ck_assert_int_eq(msocl_model_add_sphere(m, centre, 0.3f, 0.3f), MSOCL_OK);
  return m;
}

static const char *const rest_kinds[] = {"free", "on a plane",
                                         "on a sphere"};

/* The ways a scene at rest runs: integrators, BUFFER beside the layout
 * AUTO takes, and a split over two devices. */
struct rest_run {
  const char *what;
  msocl_integrator in;
  msocl_layout layout;
  int ndevices;
};
static const struct rest_run rest_runs[] = {
    {"symplectic Euler", MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_AUTO, 1},
    {"symplectic Euler, BUFFER", MSOCL_SYMPLECTIC_EULER, MSOCL_LAYOUT_BUFFER,
     1},
    {"Verlet", MSOCL_VERLET, MSOCL_LAYOUT_AUTO, 1},
    {"RK4", MSOCL_RK4, MSOCL_LAYOUT_AUTO, 1},
    {"implicit Euler", MSOCL_IMPLICIT_EULER, MSOCL_LAYOUT_AUTO, 1},
    {"symplectic Euler, two devices", MSOCL_SYMPLECTIC_EULER,
     MSOCL_LAYOUT_AUTO, 2},
};
#define REST_RUNS (int)(sizeof rest_runs / sizeof rest_runs[0])

/* The at-rest runs' runtime: up to two CPU devices, for the split. */
static char pair_spec[256];

static void setup_pair(void)
{
  ck_assert_int_eq(msocl_runtime_create(&rt, pair_spec[0] ? pair_spec
                                                          : "cpu"),
                   MSOCL_OK);
}

static int rest_devices(void)
{
  int n = 0;
  msocl_runtime_device_count(rt, &n);
  return n;
}

/* 10 000 steps at half the stable step: round-off is no blow-up, in one
 * call and in a frame loop. _i runs over scenes, then runs. */
START_TEST(at_rest_no_false_alarm)
{
  const int kind = _i % 3;
  const struct rest_run *r = &rest_runs[_i / 3];
  if (r->ndevices > rest_devices()) {
    printf("at rest, %s: skipped (one device)\n", r->what);
    return;
  }
  msocl_model *m = at_rest(kind);
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 0.5f * limit;
  o.integrator = r->in;
  o.tuning.layout = r->layout;
  o.tuning.ndevices = r->ndevices;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  msocl_energy e0, e;
  msocl_sim_energy(s, &e0);
  const int steps = r->in == MSOCL_IMPLICIT_EULER ? 2000 : 10000;
  rc = msocl_sim_step(s, steps / 2);
  ck_assert_msg(rc == MSOCL_OK, "%s, %s, one call: %s", rest_kinds[kind],
                r->what, msocl_last_error());
  for (int q = 0; q < steps / 2 / 10; q++) {
    rc = msocl_sim_step(s, 10);
    ck_assert_msg(rc == MSOCL_OK, "%s, %s, frame %d: %s", rest_kinds[kind],
                  r->what, q, msocl_last_error());
  }
  msocl_sim_energy(s, &e);
  printf("at rest, %s, %s: energy %.3g J -> %.3g J over %d steps\n",
         rest_kinds[kind], r->what, e0.total, e.total, steps);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The same scene at 1.2x the stable step blows up from its round-off: the
 * check catches it while the energy is still finite (the floor under the
 * energy scale stays below a blow-up), and restores a state still at
 * rest. */
START_TEST(at_rest_blow_up_caught)
{
  msocl_model *m = at_rest(_i);
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = 1.2f * limit;
  o.check_every = 10;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  float p0[3 * 144], p[3 * 144];
  msocl_sim_read_positions(s, p0);
  ck_assert_int_eq(msocl_sim_step(s, 10000), MSOCL_ERR_UNSTABLE);
  const char *at = strstr(msocl_last_error(), "total energy ");
  double total = NAN;
  ck_assert_ptr_nonnull(at);
  ck_assert_int_eq(sscanf(at, "total energy %lg", &total), 1);
  printf("at rest, %s, at 1.2x: %s\n", rest_kinds[_i], msocl_last_error());
  ck_assert_msg(isfinite(total), "%s", msocl_last_error());
  msocl_sim_read_positions(s, p);
  ck_assert_double_le(scene_max_diff(p, p0, 3 * 144), 1e-3);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* perturbed()'s simulation split over `parts` devices (when the runtime
 * has them; else NULL). */
static msocl_sim *perturbed_split(const msocl_model *m, float dt, int parts)
{
  msocl_sim *one = perturbed(m, MSOCL_SYMPLECTIC_EULER, dt);
  if (parts == 1)
    return one;
  float p[3 * 144];
  msocl_sim_read_positions(one, p);
  msocl_sim_destroy(one);
  if (rest_devices() < parts)
    return NULL;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.check_every = 50;
  o.tuning.ndevices = parts;
  msocl_sim *s = NULL;
  int rc = msocl_sim_create(&s, rt, m, &o);
  ck_assert_msg(rc == MSOCL_OK, "%s", msocl_last_error());
  ck_assert_int_eq(msocl_sim_write_positions(s, p), MSOCL_OK);
  return s;
}

/* A frame loop that writes more often than the check comes round (its
 * own pins, say: here the positions it read, every 10 steps) is checked
 * all the same: at 1.2x the stable step the call that completes step 50
 * reports the blow-up and leaves a finite state, where every call used
 * to return MSOCL_OK until a write met the NaNs. On one device and split
 * over two (_i). */
START_TEST(frame_loop_checked)
{
  msocl_model *m = grid();
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  msocl_sim *s = perturbed_split(m, 1.2f * limit, _i + 1);
  if (!s) {
    printf("frame loop, two devices: skipped (one device)\n");
    msocl_model_destroy(m);
    return;
  }
  int n, rc = MSOCL_OK, frame = 0;
  msocl_sim_point_count(s, &n);
  float *p = malloc(3 * (size_t)n * sizeof *p);
  for (; frame < 300; frame++) {
    rc = msocl_sim_step(s, 10);
    if (rc != MSOCL_OK)
      break;
    msocl_sim_read_positions(s, p);
    int w = msocl_sim_write_positions(s, p);
    ck_assert_msg(w == MSOCL_OK || w == MSOCL_ERR_NOT_FINITE, "frame %d: %s",
                  frame, msocl_last_error());
  }
  printf("frame loop at 1.2x, a write every 10 steps, %d device(s): frame "
         "%d: %s\n", _i + 1, frame,
         rc == MSOCL_OK ? "no blow-up reported" : msocl_last_error());
  ck_assert_int_eq(rc, MSOCL_ERR_UNSTABLE);
  ck_assert_int_eq(frame, 4); /* steps 40 to 50 */
  long long steps;
  msocl_sim_step_count(s, &steps);
  ck_assert_int_eq(steps, 0);
  msocl_sim_read_positions(s, p);
  for (int i = 0; i < 3 * n; i++)
    ck_assert(isfinite(p[i]));
  free(p);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A write the check finds sound becomes the state a blow-up restores: at
 * 1.2x, the state read and written back at step 2 (still within the
 * bound), the check at step 50 restores it. */
START_TEST(write_is_restore_point)
{
  msocl_model *m = grid();
  float limit;
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &limit);
  msocl_sim *s = perturbed(m, MSOCL_SYMPLECTIC_EULER, 1.2f * limit);
  int n;
  msocl_sim_point_count(s, &n);
  const size_t bytes = 3 * (size_t)n * sizeof(float);
  float *p2 = malloc(bytes), *v2 = malloc(bytes), *p = malloc(bytes),
        *v = malloc(bytes);
  ck_assert_int_eq(msocl_sim_step(s, 2), MSOCL_OK);
  msocl_sim_read_positions(s, p2);
  msocl_sim_read_velocities(s, v2);
  ck_assert_int_eq(msocl_sim_write_positions(s, p2), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_ERR_UNSTABLE);
  ck_assert_msg(strstr(msocl_last_error(), "blew up between steps 2 and 50"),
                "%s", msocl_last_error());
  long long steps;
  msocl_sim_step_count(s, &steps);
  ck_assert_int_eq(steps, 2);
  msocl_sim_read_positions(s, p);
  msocl_sim_read_velocities(s, v);
  ck_assert(memcmp(p, p2, bytes) == 0 && memcmp(v, v2, bytes) == 0);
  free(p2); free(v2); free(p); free(v);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* The work a write does is no blow-up: a hanging cloth whose pins the
 * loop swings by hand, lifted 0.5 m every 10 steps (200 m in all, over
 * the bound's 100 x m g extent = 140 m of lift) and its velocities halved
 * every 100 steps, runs 4000 steps without MSOCL_ERR_UNSTABLE, on one
 * device and split over two (_i). */
START_TEST(writes_do_work)
{
  if (_i + 1 > rest_devices()) {
    printf("writes do work, two devices: skipped (one device)\n");
    return;
  }
  msocl_model *m = scene_hanging(12);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt);
  o.dt *= 0.5f;
  o.tuning.ndevices = _i + 1;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  float p[3 * 144], v[3 * 144];
  for (int frame = 0; frame < 400; frame++) {
    int rc = msocl_sim_step(s, 10);
    ck_assert_msg(rc == MSOCL_OK, "frame %d: %s", frame, msocl_last_error());
    msocl_sim_read_positions(s, p);
    for (int i = 0; i < 144; i++)
      p[3 * i + 1] += 0.5f;
    const float dx = 0.01f * sinf(0.1f * (float)frame);
    p[0] += dx;          /* the pinned corners, points 0 and 11 */
    p[3 * 11] += dx;
    ck_assert_int_eq(msocl_sim_write_positions(s, p), MSOCL_OK);
    if (frame % 10 == 9) {
      msocl_sim_read_velocities(s, v);
      for (int i = 0; i < 3 * 144; i++)
        v[i] *= 0.5f;
      ck_assert_int_eq(msocl_sim_write_velocities(s, v), MSOCL_OK);
    }
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

/* A write the step's floats cannot hold is refused; one they hold whose
 * energy they do not (a point of the builder's 8 x 8 cloth 1e18 m away:
 * its springs' energy overflows a float) blows up, and the good state
 * written back afterwards runs on: the check's baseline starts afresh
 * where a replaced state's energy is not finite (it used to stay NaN,
 * every later call returning MSOCL_ERR_UNSTABLE). One device and two. */
START_TEST(recovers_from_a_ruinous_write)
{
  if (_i + 1 > rest_devices()) {
    printf("ruinous write, two devices: skipped (one device)\n");
    return;
  }
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = 8;
  msocl_model *m = NULL;
  ck_assert_int_eq(msocl_model_cloth_grid(&m, &d), MSOCL_OK);
  ck_assert_int_eq(msocl_model_pin(m, 0, 1), MSOCL_OK);
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.tuning.ndevices = _i + 1;
  msocl_sim *s = NULL;
  ck_assert_int_eq(msocl_sim_create(&s, rt, m, &o), MSOCL_OK);
  float p[3 * 64], v[3 * 64], far[3] = {2e18f, 0.0f, 0.0f};
  ck_assert_int_eq(msocl_sim_step(s, 50), MSOCL_OK);
  msocl_sim_read_positions(s, p);
  msocl_sim_read_velocities(s, v);
  ck_assert_int_eq(msocl_sim_write_range(s, 0, 5, 1, far),
                   MSOCL_ERR_BAD_VALUE);
  ck_assert_ptr_nonnull(strstr(msocl_last_error(), "exceeds"));
  far[0] = NAN;
  ck_assert_int_eq(msocl_sim_write_range(s, 1, 5, 1, far),
                   MSOCL_ERR_NOT_FINITE);
  far[0] = 1e18f;
  ck_assert_int_eq(msocl_sim_write_range(s, 0, 5, 1, far), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_step(s, 100), MSOCL_ERR_UNSTABLE);
  ck_assert_int_eq(msocl_sim_write_positions(s, p), MSOCL_OK);
  ck_assert_int_eq(msocl_sim_write_velocities(s, v), MSOCL_OK);
  for (int k = 0; k < 3; k++) {
    const int rc = msocl_sim_step(s, 100);
    ck_assert_msg(rc == MSOCL_OK, "call %d after the repair: %s", k,
                  msocl_last_error());
  }
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
}
END_TEST

int main(void)
{
  /* two PoCL CPU devices for the split runs unless the caller chose
   * otherwise; before the first OpenCL call */
  setenv("POCL_DEVICES", "pthread pthread", 0);
  scene_require_device("check_stability");
  if (scene_cpu_spec(pair_spec, sizeof pair_spec, 2) < 2)
    pair_spec[0] = '\0';
  Suite *su = suite_create("stability");
  TCase *tc = tcase_create("stability");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 300);
  tcase_add_loop_test(tc, chain_edges, 0, 3);
  tcase_add_loop_test(tc, grid_edges, 0, 3);
  tcase_add_test(tc, implicit_at_50x);
  tcase_add_test(tc, symplectic_energy_bounded);
  tcase_add_test(tc, explicit_euler_energy_growth);
  tcase_add_test(tc, stable_dt_values);
  tcase_add_test(tc, explicit_euler_dashpot_limit);
  tcase_add_test(tc, unstable_rolls_back);
  tcase_add_test(tc, check_counts_across_calls);
  suite_add_tcase(su, tc);
  /* the step limits of states a scene reaches, damping, and no limit */
  TCase *lim = tcase_create("limits");
  tcase_add_checked_fixture(lim, setup, teardown);
  tcase_set_timeout(lim, 600);
  tcase_add_loop_test(lim, pinned_cloth_safe_step, 0, 2);
  tcase_add_test(lim, stable_dt_damped);
  tcase_add_test(lim, stable_dt_refuses);
  suite_add_tcase(su, lim);
  TCase *rest = tcase_create("at rest");
  tcase_add_checked_fixture(rest, setup_pair, teardown);
  tcase_set_timeout(rest, 300);
  tcase_add_loop_test(rest, at_rest_no_false_alarm, 0, 3 * REST_RUNS);
  tcase_add_loop_test(rest, at_rest_blow_up_caught, 0, 3);
  suite_add_tcase(su, rest);
  TCase *writes = tcase_create("writes");
  tcase_add_checked_fixture(writes, setup_pair, teardown);
  tcase_set_timeout(writes, 300);
  tcase_add_loop_test(writes, frame_loop_checked, 0, 2);
  tcase_add_test(writes, write_is_restore_point);
  tcase_add_loop_test(writes, writes_do_work, 0, 2);
  tcase_add_loop_test(writes, recovers_from_a_ruinous_write, 0, 2);
  suite_add_tcase(su, writes);
  return scene_run(su);
}
