/* The device's step, redone on the host in double precision: the yardstick
 * that tests and benchmarks measure the kernels' accuracy against. It
 * follows the kernels formula for formula, integrator for integrator. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* a = f / m + g at (pos, vel); 0 at pinned points. */
static void accel(const msocl_reference *r, const double *pos,
                  const double *vel, double *a)
{
  for (int i = 0; i < r->n; i++) {
    double *ai = a + 3 * i;
    if (r->pinned[i]) {
      ai[0] = ai[1] = ai[2] = 0.0;
      continue;
    }
    msocl__ref_force(r, pos, vel, i, ai);
    for (int e = 0; e < 3; e++)
      ai[e] = ai[e] * r->inv_mass[i] + r->gravity[e];
  }
}

/* The strain sweeps of kernels/planes.cl: velocity (on r->vnew) or Provot's
 * positions (on r->pnew), Jacobi style, each point moved by the average
 * of what its springs ask. */
static void strain_velocity(msocl_reference *r)
{
  for (int it = 0; it < r->o.strain_iterations; it++) {
    for (int i = 0; i < r->n; i++) {
      double *out = r->tmp + 3 * i;
      const double *p = r->pos + 3 * i, *v = r->vnew + 3 * i;
      if (r->pinned[i]) {
        out[0] = out[1] = out[2] = 0.0;
        continue;
      }
      double dv[3] = {0, 0, 0}, weight = 0.0;
      for (int t = r->adj.off[i]; t < r->adj.off[i + 1]; t++) {
        int j = r->adj.other[t], sp = r->adj.spring[t];
        const double *q = r->pos + 3 * j, *vq = r->vnew + 3 * j;
        double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double len = sqrt(msocl__dot3(d, d));
        if (!(len > 0))
          continue;
        double allowed = ((1.0 + r->o.strain_limit) * r->rest[sp] - len) /
                         r->dt;
        double rel[3] = {vq[0] - v[0], vq[1] - v[1], vq[2] - v[2]};
        double excess = msocl__dot3(rel, d) / len - allowed;
        if (excess > 0) {
          double ask = (r->pinned[j] ? 1.0 : 0.5) * excess;
          for (int e = 0; e < 3; e++)
            dv[e] += ask * ask * d[e] / len;
          weight += ask;
        }
      }
      for (int e = 0; e < 3; e++)
        out[e] = v[e] + (weight > 0 ? dv[e] / weight : 0.0);
      msocl__ref_collide(r, p, out, 0.0);
    }
    memcpy(r->vnew, r->tmp, 3 * (size_t)r->n * sizeof(double));
  }
}

/* On r->pnew; vel (r->vnew, or Verlet's half-step velocity) takes up the
 * correction. */
static void strain_position(msocl_reference *r, double *vel)
{
  memcpy(r->a, r->pnew, 3 * (size_t)r->n * sizeof(double)); /* before */
  for (int it = 0; it < r->o.strain_iterations; it++) {
    for (int i = 0; i < r->n; i++) {
      const double *p = r->pnew + 3 * i;
      double *out = r->tmp + 3 * i;
      memcpy(out, p, 3 * sizeof(double));
      if (r->pinned[i])
        continue;
      double dp[3] = {0, 0, 0}, weight = 0.0;
      for (int t = r->adj.off[i]; t < r->adj.off[i + 1]; t++) {
        int j = r->adj.other[t], sp = r->adj.spring[t];
        const double *q = r->pnew + 3 * j;
        double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double len = sqrt(msocl__dot3(d, d));
        double over = len - (1.0 + r->o.strain_limit) * r->rest[sp];
        if (over > 0) {
          double ask = (r->pinned[j] ? 1.0 : 0.5) * over;
          for (int e = 0; e < 3; e++)
            dp[e] += ask * ask / len * d[e];
          weight += ask;
        }
      }
      for (int e = 0; e < 3; e++)
        out[e] += weight > 0 ? dp[e] / weight : 0.0;
    }
    memcpy(r->pnew, r->tmp, 3 * (size_t)r->n * sizeof(double));
  }
  /* msocl_planes_commit: velocities take up the correction */
  for (int i = 0; i < 3 * r->n; i++)
    vel[i] += (r->pnew[i] - r->a[i]) / r->dt;
}

/* Symplectic Euler's velocity pass into r->vnew. */
static void symplectic_velocity(msocl_reference *r)
{
  accel(r, r->pos, r->vel, r->a);
  for (int i = 0; i < r->n; i++) {
    double *v = r->vnew + 3 * i;
    for (int e = 0; e < 3; e++)
      v[e] = r->pinned[i] ? 0.0
                          : r->air * (r->vel[3 * i + e] + r->dt * r->a[3 * i + e]);
    if (!r->pinned[i])
      msocl__ref_collide(r, r->pos + 3 * i, v, 1.0);
  }
}

/* p' = p + dt v' into r->pnew (pinned points stay). */
static void position_pass(msocl_reference *r)
{
  for (int i = 0; i < 3 * r->n; i++)
    r->pnew[i] = r->pinned[i / 3] ? r->pos[i] : r->pos[i] + r->dt * r->vnew[i];
}

static void explicit_euler(msocl_reference *r)
{
  accel(r, r->pos, r->vel, r->a);
  for (int i = 0; i < r->n; i++) {
    double *p = r->pnew + 3 * i, *v = r->vnew + 3 * i;
    for (int e = 0; e < 3; e++) {
      p[e] = r->pos[3 * i + e] + (r->pinned[i] ? 0.0 : r->dt * r->vel[3 * i + e]);
      v[e] = r->pinned[i] ? 0.0
                          : r->air * (r->vel[3 * i + e] + r->dt * r->a[3 * i + e]);
    }
    if (!r->pinned[i])
      msocl__ref_project(r, p, v);
  }
}

static void verlet(msocl_reference *r)
{
  if (!r->acc_valid)
    accel(r, r->pos, r->vel, r->acc);
  double *vh = r->vnew; /* v+, then v' in place */
  for (int i = 0; i < r->n; i++) {
    for (int e = 0; e < 3; e++)
      vh[3 * i + e] = r->pinned[i] ? 0.0
                                   : r->vel[3 * i + e] + 0.5 * r->dt * r->acc[3 * i + e];
    if (!r->pinned[i])
      msocl__ref_collide(r, r->pos + 3 * i, vh + 3 * i, 1.0);
    for (int e = 0; e < 3; e++)
      r->pnew[3 * i + e] = r->pos[3 * i + e] + r->dt * vh[3 * i + e];
  }
  /* Provot's correction before a' is taken, so the acceleration kept for
   * the next step is the corrected positions' (integrate.c) */
  if (r->o.strain == MSOCL_STRAIN_PROVOT)
    strain_position(r, vh);
  accel(r, r->pnew, vh, r->acc);
  for (int i = 0; i < 3 * r->n; i++)
    r->vnew[i] = r->air * (vh[i] + 0.5 * r->dt * r->acc[i]);
  r->acc_valid = 1;
}

static void rk4(msocl_reference *r)
{
  const size_t n3 = 3 * (size_t)r->n;
  double *sp = r->pos, *sv = r->vel;
  const double c[3] = {0.5, 0.5, 1.0};
  for (int q = 0; q < 4; q++) {
    accel(r, sp, sv, r->a);
    double w = (q == 0 || q == 3) ? 1.0 : 2.0;
    for (size_t i = 0; i < n3; i++) {
      r->sum_p[i] = (q == 0 ? 0.0 : r->sum_p[i]) + w * sv[i];
      r->sum_v[i] = (q == 0 ? 0.0 : r->sum_v[i]) + w * r->a[i];
    }
    if (q == 3)
      break;
    double *np = r->stage_p[q & 1], *nv = r->stage_v[q & 1];
    for (size_t i = 0; i < n3; i++) {
      /* a pinned point's stages stay where it is, as the kernels' */
      np[i] = r->pinned[i / 3] ? r->pos[i] : r->pos[i] + c[q] * r->dt * sv[i];
      nv[i] = r->pinned[i / 3] ? 0.0 : r->vel[i] + c[q] * r->dt * r->a[i];
    }
    sp = np;
    sv = nv;
  }
  for (int i = 0; i < r->n; i++) {
    double *p = r->pnew + 3 * i, *v = r->vnew + 3 * i;
    for (int e = 0; e < 3; e++) {
      p[e] = r->pos[3 * i + e] +
             (r->pinned[i] ? 0.0 : r->dt / 6.0 * r->sum_p[3 * i + e]);
      v[e] = r->pinned[i] ? 0.0
                          : r->air * (r->vel[3 * i + e] +
                                      r->dt / 6.0 * r->sum_v[3 * i + e]);
    }
    if (!r->pinned[i])
      msocl__ref_project(r, p, v);
  }
}

int msocl_reference_step(msocl_reference *r, int n)
{
  msocl__clear_error();
  if (!r)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "reference is NULL");
  if (n < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "step count %d is negative", n);
  /* Verlet's a at the state the call starts from, before pins move (the
   * kernels take it when the state enters their planes) */
  if (n > 0 && r->tm > 0 && r->o.integrator == MSOCL_VERLET &&
      !r->acc_valid) {
    accel(r, r->pos, r->vel, r->acc);
    r->acc_valid = 1;
  }
  for (int k = 0; k < n; k++) {
    msocl__ref_pins(r, k, n);
    msocl__ref_colliders(r, k, n);
    msocl__ref_wind(r);
    msocl__ref_field(r);
    msocl__ref_soft_pins(r, k, n);
    switch (r->o.integrator) {
    case MSOCL_SYMPLECTIC_EULER:
    case MSOCL_IMPLICIT_EULER:
      if (r->o.integrator == MSOCL_SYMPLECTIC_EULER)
        symplectic_velocity(r);
      else
        msocl__ref_implicit_velocity(r);
      if (r->o.strain == MSOCL_STRAIN_VELOCITY)
        strain_velocity(r);
      position_pass(r);
      break;
    case MSOCL_EXPLICIT_EULER: explicit_euler(r); break;
    case MSOCL_VERLET: verlet(r); break;
    case MSOCL_RK4: rk4(r); break;
    }
    if (r->o.strain == MSOCL_STRAIN_PROVOT && r->o.integrator != MSOCL_VERLET)
      strain_position(r, r->vnew);
    double *t = r->pos;
    r->pos = r->pnew;
    r->pnew = t;
    t = r->vel;
    r->vel = r->vnew;
    r->vnew = t;
  }
  if (n > 0) {
    msocl__ref_pins(r, n, n);
    msocl__ref_soft_pins(r, n, n);
    msocl__ref_colliders(r, n, n);
  }
  return msocl__ref_cg_report(r, MSOCL_OK, n);
}
