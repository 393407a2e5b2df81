/* The end of a stepping call: what its engines' CG missed, said once. */
#include "config.h"
#include "sim.h"

/* Every step is taken even when its CG missed: the state then holds the
 * solver's last iterate, and the code says so once, for the whole call. */
int msocl__cg_report(msocl_sim *s, int rc, int n)
{
  const msocl__engine *e = s->part[0];
  const int missed = e->cg_missed, it = e->cg_worst_iterations;
  const double res = e->cg_worst_residual;
  for (int d = 0; d < s->nparts; d++)
    s->part[d]->cg_missed = 0;
  if (rc != MSOCL_OK || missed == 0)
    return rc;
  return msocl__fail(
      MSOCL_ERR_NO_CONVERGENCE,
      "implicit Euler: CG stopped above the tolerance %g in %d of %d steps "
      "(worst: relative residual %g after %d iterations, cap %d); the steps "
      "were taken with the solver's last iterate",
      (double)s->o.cg_tolerance, missed, n, res, it, s->o.cg_max_iterations);
}
