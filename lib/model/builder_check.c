/* Argument checks the model builders (cloth, lattice, solid) share, with
 * messages that name the builder and the field. */
#include "config.h"
#include "internal.h"

#include <math.h>

int msocl__check_finite(const char *builder, const char *what,
                        const float *x, int n)
{
  for (int c = 0; c < n; c++)
    if (!isfinite(x[c]))
      return n > 1 ? msocl__fail(MSOCL_ERR_NOT_FINITE,
                                 "%s: %s[%d] = %g is not finite", builder,
                                 what, c, x[c])
                   : msocl__fail(MSOCL_ERR_NOT_FINITE,
                                 "%s: %s %g is not finite", builder, what,
                                 x[c]);
  return MSOCL_OK;
}

int msocl__check_coef(const char *builder, const char *what, float x)
{
  if (x < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "%s: %s %g must be >= 0",
                       builder, what, x);
  return MSOCL_OK;
}
