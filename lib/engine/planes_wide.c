/* Which planes kernels run in explicit vectors (kernels/planes_wide*.cl,
 * sixteen points a work-item), and whether their force gathers the
 * positions from a float4 copy (planes_pack.c). */
#include "planes.h"

static int wide_mode = 0; /* tests: msocl__pl_wide_mode */

void msocl__pl_wide_mode(int mode)
{
  wide_mode = mode;
}

/* Whether PoCL vectorises the scalar kernels' gathers with the CPU's own
 * gather instructions: where its vectors are 16 floats (AVX-512). On
 * AVX2 (8) LLVM's cost model leaves them scalar (docs/PERFORMANCE.md). */
static int hardware_gathers(const msocl__engine *s)
{
  cl_uint w = 0;
  clGetDeviceInfo(s->dev->id, CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT, sizeof w,
                  &w, NULL);
  return w >= 16;
}

/* Whether the planes kernels take their planes_wide.cl twins:
 * on a CPU device, where PoCL may leave the scalar kernels unvectorised;
 * one engine (they launch over every point), precise math (bitwise the
 * scalar kernels'); a cloth grid or lattice whose rows come in
 * work-groups of a work-item's points or more, or BUFFER's or EDGES's
 * table where the scalar kernels' gathers stay scalar (with hardware
 * gathers PoCL's own vectors ran BUFFER 1.05-1.5x the wide kernels). */
int msocl__pl_wide(const msocl__engine *s)
{
  if (s->dev->info.type != MSOCL_DEVICE_CPU || s->lo != 0 ||
      s->hi != s->n || s->o.math != MSOCL_MATH_PRECISE)
    return 0;
  if (s->lay.kind == MSOCL_LAYOUT_GRID)
    return s->pl_group >= MSOCL__WIDE_W;
  return (s->lay.kind == MSOCL_LAYOUT_BUFFER ||
          s->lay.kind == MSOCL_LAYOUT_EDGES) &&
         (wide_mode > 0 || (wide_mode == 0 && !hardware_gathers(s)));
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
