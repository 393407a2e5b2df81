/* Backward Euler on the host in double: the same linearised system and
 * matrix-free conjugate gradients as kernels/planes_implicit.cl. */
#include "config.h"
#include "reference_state.h"

#include <math.h>
#include <string.h>

/* J (dx) of a spring from p to q (clamped as on the device). */
static void jacobian(const double *p, const double *q, double rest, double k,
                     const double *dx, double *out)
{
  double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  double len = sqrt(msocl__dot3(d, d));
  out[0] = out[1] = out[2] = 0.0;
  if (!(len > 0))
    return;
  double u[3] = {d[0] / len, d[1] / len, d[2] / len};
  double t = 1.0 - rest / len, ud = msocl__dot3(u, dx);
  if (t < 0)
    t = 0;
  for (int e = 0; e < 3; e++)
    out[e] = k * (ud * u[e] + t * (dx[e] - ud * u[e]));
}

/* y = A x, A = M + dt C_visc - dt D - dt^2 K; identity at pinned points. */
static void apply(const msocl_reference *r, const double *x, double *y)
{
  for (int i = 0; i < r->n; i++) {
    const double *xi = x + 3 * i, *p = r->pos + 3 * i;
    double *yi = y + 3 * i;
    if (r->pinned[i]) {
      memcpy(yi, xi, 3 * sizeof(double));
      continue;
    }
    double kx[3] = {0, 0, 0}, dx[3] = {0, 0, 0}, t[3];
    for (int s = r->adj.off[i]; s < r->adj.off[i + 1]; s++) {
      int j = r->adj.other[s], sp = r->adj.spring[s];
      const double *q = r->pos + 3 * j;
      double dp[3] = {x[3 * j] - xi[0], x[3 * j + 1] - xi[1],
                      x[3 * j + 2] - xi[2]};
      jacobian(p, q, r->rest[sp], r->k[sp], dp, t);
      double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      double len2 = msocl__dot3(d, d);
      double c = len2 > 0 ? r->damp[sp] * msocl__dot3(d, dp) / len2 : 0.0;
      for (int e = 0; e < 3; e++) {
        kx[e] += t[e];
        dx[e] += c * d[e];
      }
    }
    for (int e = 0; e < 3; e++)
      yi[e] = (r->mass[i] + r->dt * r->viscous) * xi[e] - r->dt * dx[e] -
              r->dt * r->dt * kx[e];
  }
}

static double dot(const double *a, const double *b, int n3)
{
  double s = 0.0;
  for (int i = 0; i < n3; i++)
    s += a[i] * b[i];
  return s;
}

int msocl__ref_cg_report(msocl_reference *r, int rc, int n)
{
  const int missed = r->cg_missed;
  r->cg_missed = 0;
  if (rc != MSOCL_OK || missed == 0)
    return rc;
  return msocl__fail(
      MSOCL_ERR_NO_CONVERGENCE,
      "reference implicit Euler: CG stopped above the tolerance %g in %d of "
      "%d steps (worst: relative residual %g after %d iterations, cap %d); "
      "the steps were taken with the solver's last iterate",
      (double)r->o.cg_tolerance, missed, n, r->cg_worst_residual,
      r->cg_worst_iterations, r->o.cg_max_iterations);
}

void msocl__ref_implicit_velocity(msocl_reference *r)
{
  const int n3 = 3 * r->n;
  double *x = r->stage_p[0], *res = r->stage_p[1], *p = r->stage_v[0],
         *ap = r->stage_v[1];
  for (int i = 0; i < r->n; i++) {
    double b[3] = {0, 0, 0};
    if (!r->pinned[i]) {
      double f[3], kv[3] = {0, 0, 0}, t[3];
      const double *pi = r->pos + 3 * i, *vi = r->vel + 3 * i;
      msocl__ref_force(r, r->pos, r->vel, i, f);
      for (int s = r->adj.off[i]; s < r->adj.off[i + 1]; s++) {
        int j = r->adj.other[s], sp = r->adj.spring[s];
        double dv[3] = {r->vel[3 * j] - vi[0], r->vel[3 * j + 1] - vi[1],
                        r->vel[3 * j + 2] - vi[2]};
        jacobian(pi, r->pos + 3 * j, r->rest[sp], r->k[sp], dv, t);
        for (int e = 0; e < 3; e++)
          kv[e] += t[e];
      }
      for (int e = 0; e < 3; e++)
        b[e] = r->dt * (f[e] + r->mass[i] * r->gravity[e] + r->dt * kv[e]);
    }
    for (int e = 0; e < 3; e++) {
      x[3 * i + e] = 0.0;
      res[3 * i + e] = p[3 * i + e] = b[e];
    }
  }
  double bb = dot(res, res, n3), rr = bb;
  double goal = (double)r->o.cg_tolerance * r->o.cg_tolerance * bb;
  int it = 0;
  while (rr > goal && it < r->o.cg_max_iterations) {
    apply(r, p, ap);
    double pap = dot(p, ap, n3);
    if (!(pap > 0))
      break;
    double alpha = rr / pap;
    for (int i = 0; i < n3; i++) {
      x[i] += alpha * p[i];
      res[i] -= alpha * ap[i];
    }
    double rr_new = dot(res, res, n3), beta = rr_new / rr;
    for (int i = 0; i < n3; i++)
      p[i] = res[i] + beta * p[i];
    rr = rr_new;
    it++;
  }
  r->cg_iterations = it;
  r->cg_residual = bb > 0 ? sqrt(rr / bb) : 0.0;
  if (!(rr <= goal) &&
      (r->cg_missed++ == 0 ||
       (!isnan(r->cg_worst_residual) &&
        (isnan(r->cg_residual) || r->cg_residual > r->cg_worst_residual)))) {
    r->cg_worst_residual = r->cg_residual; /* as msocl__cg_note */
    r->cg_worst_iterations = it;
  }
  for (int i = 0; i < r->n; i++) {
    double *v = r->vnew + 3 * i;
    if (r->pinned[i]) {
      v[0] = v[1] = v[2] = 0.0;
      continue;
    }
    for (int e = 0; e < 3; e++)
      v[e] = r->air * (r->vel[3 * i + e] + x[3 * i + e]);
    msocl__ref_collide(r, r->pos + 3 * i, v, 1.0);
  }
}
