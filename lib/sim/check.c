/* The blow-up check's measures: the energy of the whole simulation, its
 * scale and bound, the saved state to go back to, and a write's part. The
 * stepping (sim_step.c) decides when; these say what. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <string.h>

/* Energy of the whole state: each engine sums its own points. */
int msocl__sim_energy(msocl_sim *s, msocl_energy *e)
{
  memset(e, 0, sizeof *e);
  for (int d = 0; d < s->nparts; d++) {
    msocl_energy p;
    int rc = msocl__energy(s->part[d], &p);
    if (rc != MSOCL_OK)
      return rc;
    e->kinetic += p.kinetic;
    e->spring += p.spring;
    e->gravity += p.gravity;
  }
  e->total = e->kinetic + e->spring + e->gravity;
  return MSOCL_OK;
}

/* The blow-up check's scale for a state of energy e: its kinetic and
 * spring energy, the work gravity could do across the scene's extent, and
 * a floor from its springs: their energy with each one stretched by 1e-3
 * of its rest length. A scene at rest without gravity holds only
 * round-off (which grows with the steps); the floor keeps its bound above
 * that, and at energy_factor 100 allows every spring 1% strain, which a
 * blow-up passes within a few steps. */
static double scale(const msocl_sim *s, const msocl_energy *e)
{
  const cl_float4 *g = &s->part[0]->gravity;
  double gn = sqrt((double)g->s[0] * g->s[0] + (double)g->s[1] * g->s[1] +
                   (double)g->s[2] * g->s[2]);
  return e->kinetic + e->spring + s->total_mass * gn * s->extent + s->efloor;
}

double msocl__check_bound(const msocl_sim *s)
{
  return s->e0 + s->o.energy_factor * s->escale;
}

/* The baseline: energy at the start and its scale; after writes, the
 * written state's energy added to e0 (which the first write took the
 * replaced state's off), and the scale kept at the larger. A sum that is
 * not finite accounts for nothing: the written state starts afresh. */
int msocl__check_baseline(msocl_sim *s)
{
  msocl_energy e;
  int rc = msocl__sim_energy(s, &e);
  if (rc != MSOCL_OK)
    return rc;
  const double sc = scale(s, &e);
  if (s->e0_valid && s->moved && isfinite(s->e0 + e.total)) {
    s->e0 += e.total;
    s->escale = sc > s->escale ? sc : s->escale;
    s->wrote = 1;
  } else {
    s->e0 = e.total;
    s->escale = sc;
  }
  s->e0_valid = 1;
  s->moved = 0;
  return MSOCL_OK;
}

/* Saves (to_backup) or restores each engine's whole state. */
int msocl__check_backup(msocl_sim *s, int to_backup)
{
  for (int d = 0; d < s->nparts; d++)
    MSOCL__TRY(msocl__state_backup(s->part[d], to_backup));
  return MSOCL_OK;
}

/* A write replaces the state: the work it does moves the baseline (the
 * replaced state's energy comes off e0 here, the written state's goes on
 * at the next step, which saves it as the state to restore), so the check
 * judges only what the steps did. A replaced state already past the bound
 * blew up in the steps since the last save; the check reports that and
 * restores the saved state, undoing the writes since. A replaced state
 * (or a baseline) whose energy is not finite has no work to take off: the
 * next step takes the written state's energy as a new start. */
int msocl__check_write(msocl_sim *s)
{
  if (s->o.check_every <= 0 || !s->e0_valid || s->moved || s->blown)
    return MSOCL_OK;
  msocl_energy e;
  int rc = msocl__sim_energy(s, &e);
  if (rc != MSOCL_OK)
    return rc;
  if (s->since_check > 0 && !(isfinite(e.total) && e.total <= msocl__check_bound(s))) {
    s->blown = 1;
    s->blown_step = s->steps;
    s->blown_total = e.total;
  } else if (isfinite(e.total) && isfinite(s->e0)) {
    s->e0 -= e.total;
    s->moved = 1;
  } else {
    s->e0_valid = 0;
    s->moved = 1;
  }
  return MSOCL_OK;
}

