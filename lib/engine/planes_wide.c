/* Which planes kernels run in explicit vectors (kernels/planes_wide*.cl,
 * sixteen points a work-item), and whether their force gathers the
 * positions from a float4 copy (planes_pack.c). */
#include "planes.h"

/* Whether the planes kernels take their planes_wide.cl twins:
 * on a CPU device, where PoCL may leave the scalar kernels unvectorised;
 * one engine (they launch over every point), precise math (bitwise the
 * scalar kernels'); BUFFER's or EDGES's table, or a cloth grid or lattice
 * whose rows come in work-groups of a work-item's points or more. */
int msocl__pl_wide(const msocl__engine *s)
{
  if (s->dev->info.type != MSOCL_DEVICE_CPU || s->lo != 0 ||
      s->hi != s->n || s->o.math != MSOCL_MATH_PRECISE)
    return 0;
  return s->lay.kind == MSOCL_LAYOUT_BUFFER ||
         s->lay.kind == MSOCL_LAYOUT_EDGES ||
         (s->lay.kind == MSOCL_LAYOUT_GRID && s->pl_group >= MSOCL__WIDE_W);
}

int msocl__pl_gather4(const msocl__engine *s)
{
  return msocl__pl_wide(s) && s->lay.kind != MSOCL_LAYOUT_GRID;
}

/* Planes kernel q's twin in explicit vectors (planes_wide.cl,
 * planes_wide_strain.cl, planes_wide_implicit.cl), or NULL: every
 * gathering kernel, and Verlet's drift. */
const char *msocl__pl_wide_name(int q)
{
  switch (q) {
  case PL_VELOCITY:
    return "msocl_planes_wide_velocity";
  case PL_FUSED:
    return "msocl_planes_wide_fused";
  case PL_KICK:
    return "msocl_planes_wide_vkick";
  case PL_RK4:
    return "msocl_planes_wide_rk4_first";
  case PL_RK4_MID:
    return "msocl_planes_wide_rk4_middle";
  case PL_RK4_LAST:
    return "msocl_planes_wide_rk4_last";
  case PL_EULER:
    return "msocl_planes_wide_euler";
  case PL_DRIFT:
    return "msocl_planes_wide_drift";
  case PL_STRAIN:
    return "msocl_planes_wide_strain";
  case PL_STRAIN_V:
    return "msocl_planes_wide_strain_v";
  case PL_IE_RHS:
    return "msocl_planes_wide_ie_rhs";
  case PL_IE_APPLY:
    return "msocl_planes_wide_ie_apply";
  default:
    return NULL;
  }
}
