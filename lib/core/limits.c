/* The magnitudes a step's float arithmetic stays finite within (msocl.h),
 * checked alike where a model is built and where a running simulation or
 * the reference takes new values. */
#include "config.h"
#include "internal.h"

#include <math.h>

int msocl__check_damping(int air, float value)
{
  const char *what = air ? "air resistance" : "viscous damping";
  if (!isfinite(value))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s %g is not finite", what,
                       (double)value);
  if (air ? !(value > 0.0f && value <= 1.0f) : value < 0.0f)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "%s %g must be %s", what,
                       (double)value, air ? "in (0, 1]" : ">= 0");
  return MSOCL_OK;
}

int msocl__check_triples(const char *what, const char *item, const float *xyz,
                         int n, const int *idx, int first, double max)
{
  for (int q = 0; q < 3 * n; q++) {
    const int at = idx ? idx[q / 3] : first + q / 3;
    if (!isfinite(xyz[q]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE, "%s: %s %d: %c = %g is not "
                         "finite", what, item, at, "xyz"[q % 3],
                         (double)xyz[q]);
    if (fabs(xyz[q]) > max)
      return msocl__fail(MSOCL_ERR_BAD_VALUE, "%s: %s %d: |%c| = %g exceeds "
                         "%g, past which a step's float arithmetic overflows",
                         what, item, at, "xyz"[q % 3], fabs(xyz[q]), max);
  }
  return MSOCL_OK;
}
