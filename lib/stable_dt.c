/* The largest stable time step of a model under each integrator.
 *
 * The highest eigenfrequency w of the linearised system, w^2 = the largest
 * eigenvalue of M^-1/2 K M^-1/2, is bounded by Gershgorin's circle theorem
 * (the largest absolute row sum of that symmetric matrix), taken over the
 * 3n scalar rows with each spring's 3x3 stiffness block
 * k (u u^T + (1 - r/l)(I - u u^T)) at the model's current positions, and
 * without pinned points (their rows and columns drop out). For a chain this
 * bound is tight; for the paper's cloth grid it is about 12% above the true
 * w (measured against a dense eigensolver on 8x8 to 16x16 grids).
 *
 * Limits for an undamped oscillator of frequency w (the stability regions
 * of the methods on the imaginary axis): symplectic Euler and velocity
 * Verlet h w < 2; classic RK4 h w <= 2 sqrt 2; explicit Euler has none on
 * that axis - a mode damped at rate g needs h <= g / w^2, so viscous
 * damping c/m gives h <= (c/m) / w^2 and dashpots c >= beta k on every
 * spring (rate >= beta w^2) give h <= beta; backward Euler is
 * unconditionally stable. Dashpots and viscous damping
 * also bound explicit steps: the damping matrix's Gershgorin bound d needs
 * h d <= 2. */
#include "config.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>

/* Gershgorin bounds of the stiffness (w^2) and damping (d) operators. */
static int bounds(const msocl_model *m, double *w2, double *d, double *gmin,
                  double *beta)
{
  /* own[9i..]: point i's assembled diagonal block (row sums of absolute
   * values are taken after assembly: the blocks of crossing springs
   * partly cancel); off[3i + a]: absolute sums of the off-diagonal rows. */
  double *own = calloc(9 * (size_t)m->n, sizeof *own);
  double *off = calloc(3 * (size_t)m->n, sizeof *off);
  double *drow = calloc((size_t)m->n, sizeof *drow);
  if (!own || !off || !drow) {
    free(own);
    free(off);
    free(drow);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "stable_dt");
  }
  *beta = INFINITY;
  for (int s = 0; s < m->ns; s++) {
    int i = m->ij[2 * s], j = m->ij[2 * s + 1];
    double u[3], len = 0.0;
    for (int a = 0; a < 3; a++) {
      u[a] = (double)m->pos[3 * j + a] - m->pos[3 * i + a];
      len += u[a] * u[a];
    }
    len = sqrt(len);
    if (!(len > 0.0))
      continue;
    for (int a = 0; a < 3; a++)
      u[a] /= len;
    double k = m->k[s], t = 1.0 - m->rest[s] / len;
    double mij = sqrt((double)m->mass[i] * m->mass[j]);
    for (int a = 0; a < 3; a++) {
      double blk = 0.0;
      for (int b = 0; b < 3; b++) {
        double e = k * (u[a] * u[b] + t * ((a == b) - u[a] * u[b]));
        own[9 * i + 3 * a + b] += e;
        own[9 * j + 3 * a + b] += e;
        blk += fabs(e);
      }
      if (!m->pinned[j])
        off[3 * i + a] += blk / mij;
      if (!m->pinned[i])
        off[3 * j + a] += blk / mij;
    }
    double c = m->damp ? m->damp[s] : 0.0;
    if (k > 0.0 && c / k < *beta)
      *beta = c / k;
    drow[i] += 2.0 * c / m->mass[i];
    drow[j] += 2.0 * c / m->mass[j];
  }
  *w2 = 0.0;
  *d = 0.0;
  *gmin = INFINITY;
  for (int i = 0; i < m->n; i++) {
    if (m->pinned[i])
      continue;
    for (int a = 0; a < 3; a++) {
      double r = off[3 * i + a];
      for (int b = 0; b < 3; b++)
        r += fabs(own[9 * i + 3 * a + b]) / m->mass[i];
      if (r > *w2)
        *w2 = r;
    }
    double g = m->viscous / m->mass[i];
    if (drow[i] + g > *d)
      *d = drow[i] + g;
    if (g < *gmin)
      *gmin = g;
  }
  free(own);
  free(off);
  free(drow);
  return MSOCL_OK;
}

int msocl_stable_dt(const msocl_model *m, msocl_integrator integrator,
                    float *dt)
{
  msocl__clear_error();
  if (!dt)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "dt out-pointer is NULL");
  *dt = 0.0f;
  int rc = msocl_model_validate(m);
  if (rc != MSOCL_OK)
    return rc;
  if (integrator == MSOCL_IMPLICIT_EULER) {
    *dt = INFINITY;
    return MSOCL_OK;
  }
  double w2 = 0.0, d = 0.0, gmin = 0.0, beta = 0.0;
  rc = bounds(m, &w2, &d, &gmin, &beta);
  if (rc != MSOCL_OK)
    return rc;
  double w = sqrt(w2), h = INFINITY;
  switch (integrator) {
  case MSOCL_SYMPLECTIC_EULER:
  case MSOCL_VERLET:
    h = 2.0 / w;
    break;
  case MSOCL_RK4:
    h = 2.0 * sqrt(2.0) / w;
    break;
  case MSOCL_EXPLICIT_EULER:
    if (!(gmin > 0.0) && !(beta > 0.0) && w2 > 0.0)
      return msocl__fail(MSOCL_ERR_UNSTABLE,
                         "explicit Euler has no stable step for undamped "
                         "springs (highest frequency %g rad/s): add viscous "
                         "damping, a dashpot on every spring, or choose "
                         "another integrator",
                         w);
    h = w2 > 0.0 ? gmin / w2 : INFINITY;
    /* dashpots c >= beta k on every spring damp each mode at rate
     * >= beta w^2, which makes h <= beta stable at any frequency */
    if (beta > h && isfinite(beta))
      h = beta;
    break;
  default:
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown integrator %d",
                       (int)integrator);
  }
  if (d > 0.0 && 2.0 / d < h)
    h = 2.0 / d;
  *dt = (float)h;
  return MSOCL_OK;
}
