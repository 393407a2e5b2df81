/* Where the data a split's exchange moves lies in an engine's buffers:
 * three slices, one a plane, each over the padded positions of the
 * range's first to last point (a grid's row padding between them is
 * zeros on every engine, so copying it changes nothing). */
#include "config.h"
#include "engine.h"

/* Where point k sits in a plane (kernels/planes.cl's MSOCL_PLANES_AT). */
static size_t padded(const msocl__engine *s, int k)
{
  if (s->lay.kind != MSOCL_LAYOUT_GRID)
    return (size_t)k;
  const int nx = s->lay.grid_nx, ny = s->lay.grid_ny;
  const size_t x = (size_t)(k % nx), y = (size_t)(k / nx % ny),
               z = (size_t)(k / nx / ny);
  const size_t row = (y + 2) * (size_t)s->pl_pitch + x + 2;
  return s->lay.grid_nz > 0 ? (z + 2) * (size_t)s->pl_slab + row : row;
}

int msocl__exchange_slices(const msocl__engine *s, int a, int b,
                           size_t off[3], size_t *len)
{
  const size_t first = padded(s, a), plane = (size_t)s->pl_plane;
  *len = (padded(s, b - 1) + 1 - first) * sizeof(float);
  for (int c = 0; c < 3; c++)
    off[c] = ((size_t)c * plane + first) * sizeof(float);
  return 3;
}

/* The planes' buffer an exchange bit names:
 * RK4's stages alternate between the stage sets, the CG direction is the
 * first stage velocities (planes_implicit.c). */
cl_mem msocl__planes_exchange_buffer(const msocl__engine *s, unsigned bit)
{
  const int r = s->pl_set, w = 1 - r;
  switch (bit) {
  case MSOCL__X_POS_W: return s->pl_p[w];
  case MSOCL__X_VEL_W: return s->pl_v[w];
  case MSOCL__X_VEL_R: return s->pl_v[r];
  case MSOCL__X_STAGE0: return s->pl_sp[0];
  case MSOCL__X_STAGE1: return s->pl_sp[1];
  case MSOCL__X_STAGEV0: return s->pl_sv[0];
  case MSOCL__X_STAGEV1: return s->pl_sv[1];
  case MSOCL__X_CG_P: return s->pl_sv[0];
  }
  return NULL;
}
