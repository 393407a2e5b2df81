/* The largest stable time step of a model under each integrator.
 *
 * The highest eigenfrequency w of the linearised system, w^2 = the largest
 * eigenvalue of M^-1/2 K M^-1/2, is bounded by Gershgorin's circle theorem
 * (the largest absolute row sum of that symmetric matrix), taken over the
 * 3n scalar rows with each spring's 3x3 stiffness block
 * k (u u^T + (1 - r/l)(I - u u^T)), and without pinned points (their rows
 * and columns drop out). At given positions (msocl_stable_dt: the model's)
 * this bound is tight for a chain and about 12% above the true w for the
 * paper's cloth grid (measured against a dense eigensolver on 8x8 to 16x16
 * grids), but it holds for that state only: a stretched spring stiffens
 * sideways (1 - r/l > 0), so a hanging cloth reaches states with a higher
 * w. Every block is at most k I in any state (its eigenvalues are k and
 * k (1 - r/l) < k), so K is at most the springs' weighted graph Laplacian
 * times I, and that Laplacian's Gershgorin bound holds for every state the
 * model can reach (msocl_safe_dt, which takes 0.7 of it for the
 * symplectic methods).
 *
 * Limits for a mode of frequency w damped at rate g (the stability regions
 * of the methods): symplectic Euler and velocity Verlet
 * h^2 w^2 + 2 h g < 4 (h w < 2 undamped); classic RK4 h w <= 2 sqrt 2
 * while g <= 0.58 w, and a mode damped more has |lambda| < g / 0.58, so
 * h <= 1.5 / g keeps h lambda inside the region's smallest radius in the
 * left half plane, 2.61; explicit
 * Euler has none on the imaginary axis - it needs h <= g / w^2, so viscous
 * damping c/m gives h <= (c/m) / w^2 and dashpots c >= beta k on every
 * spring (rate >= beta w^2) give h <= beta, and h g <= 2 for overdamped
 * modes; backward Euler is unconditionally stable. The damping operator's
 * Gershgorin bound d stands in for every mode's g. */
#include "config.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>

/* Gershgorin bounds of the stiffness (w^2) and damping (d) operators at
 * positions pos, or (pos NULL) over every state, each block at k I. */
static int bounds(const msocl_model *m, const float *pos, double *w2,
                  double *d, double *gmin, double *beta)
{
  /* own[9i..]: point i's assembled diagonal block (row sums of absolute
   * values are taken after assembly: the blocks of crossing springs
   * partly cancel); off[3i + a]: absolute sums of the off-diagonal rows. */
  double *own = calloc(9 * (size_t)m->n, sizeof *own);
  double *off = calloc(3 * (size_t)m->n, sizeof *off);
  double *drow = calloc((size_t)m->n, sizeof *drow);
  int rc = MSOCL_OK;
  if (!own || !off || !drow) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "stable_dt");
    goto out;
  }
  *beta = INFINITY;
  for (int s = 0; s < m->ns; s++) {
    int i = m->ij[2 * s], j = m->ij[2 * s + 1];
    double k = m->k[s], u[3] = {0.0, 0.0, 0.0}, t = 1.0; /* k I */
    if (pos) {
      double len = 0.0;
      for (int a = 0; a < 3; a++) {
        u[a] = (double)pos[3 * j + a] - pos[3 * i + a];
        len += u[a] * u[a];
      }
      len = sqrt(len);
      if (len > 0.0) {
        for (int a = 0; a < 3; a++)
          u[a] /= len;
        t = 1.0 - m->rest[s] / len;
      } else if (k > 0.0 && m->rest[s] > 0.0) {
        /* 1 - r/l has no limit there: the linearisation does not exist */
        rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "spring %d joins points %d and %d, which coincide "
                         "(rest length %g): no stable step at this state; "
                         "move them apart, or use msocl_safe_dt, which "
                         "holds for every state",
                         s, i, j, (double)m->rest[s]);
        goto out;
      }
    }
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
out:
  free(own);
  free(off);
  free(drow);
  return rc;
}

/* The step for the bounds w2 and d under the integrator. */
static int limit(msocl_integrator integrator, double w2, double d,
                 double gmin, double beta, float *dt)
{
  double w = sqrt(w2), h = INFINITY;
  switch (integrator) {
  case MSOCL_IMPLICIT_EULER:
    *dt = INFINITY;
    return MSOCL_OK;
  case MSOCL_SYMPLECTIC_EULER:
  case MSOCL_VERLET:
    /* the positive root of h^2 w^2 + 2 h d = 4 */
    h = 4.0 / (d + sqrt(d * d + 4.0 * w2));
    break;
  case MSOCL_RK4:
    h = 2.0 * sqrt(2.0) / w;
    if (d > 0.0 && 1.5 / d < h)
      h = 1.5 / d;
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
    if (d > 0.0 && 2.0 / d < h)
      h = 2.0 / d;
    break;
  default:
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown integrator %d",
                       (int)integrator);
  }
  if (!isfinite(h))
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "no spring stiffness and no damping bound the step "
                       "(no springs, all stiffness 0, or only pinned "
                       "points): any step is stable, choose one for "
                       "accuracy");
  *dt = (float)h;
  return MSOCL_OK;
}

static int stable(const msocl_model *m, const float *xyz, int any,
                  msocl_integrator integrator, float *dt)
{
  msocl__clear_error();
  if (!dt)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "dt out-pointer is NULL");
  *dt = 0.0f;
  int rc = msocl_model_validate(m);
  if (rc != MSOCL_OK)
    return rc;
  if ((unsigned)integrator > (unsigned)MSOCL_IMPLICIT_EULER)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown integrator %d",
                       (int)integrator);
  if (integrator == MSOCL_IMPLICIT_EULER) {
    *dt = INFINITY;
    return MSOCL_OK;
  }
  double w2 = 0.0, d = 0.0, gmin = 0.0, beta = 0.0;
  rc = bounds(m, any ? NULL : xyz ? xyz : m->pos, &w2, &d, &gmin, &beta);
  if (rc != MSOCL_OK)
    return rc;
  return limit(integrator, w2, d, gmin, beta, dt);
}

int msocl_stable_dt(const msocl_model *m, msocl_integrator integrator,
                    float *dt)
{
  return stable(m, NULL, 0, integrator, dt);
}

int msocl_stable_dt_at(const msocl_model *m, const float *xyz,
                       msocl_integrator integrator, float *dt)
{
  if (!xyz && m) {
    msocl__clear_error();
    if (dt)
      *dt = 0.0f;
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "xyz is NULL");
  }
  if (m) {
    msocl__clear_error();
    const int rc = msocl__check_triples("msocl_stable_dt_at", "point", xyz,
                                        m->n, NULL, 0, MSOCL__COORD_MAX);
    if (rc != MSOCL_OK) {
      if (dt)
        *dt = 0.0f;
      return rc;
    }
  }
  return stable(m, xyz, 0, integrator, dt);
}

/* Symplectic Euler and Verlet keep a nonlinear undamped model's energy
 * bounded only for a time that grows exponentially as h w falls below the
 * limit, and close to it that time is short; the margin is chosen from
 * long runs of the pinned default cloth (docs/STABILITY.md). */
#define SYMPLECTIC_MARGIN 0.7

int msocl_safe_dt(const msocl_model *m, msocl_integrator integrator,
                  float *dt)
{
  int rc = stable(m, NULL, 1, integrator, dt);
  if (rc == MSOCL_OK && (integrator == MSOCL_SYMPLECTIC_EULER ||
                         integrator == MSOCL_VERLET))
    *dt *= (float)SYMPLECTIC_MARGIN;
  return rc;
}
