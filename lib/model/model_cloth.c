/* The paper's cloth: a grid of points with stretch, shear and bend springs,
 * built through the public model calls. */
#include <limits.h>
#include <math.h>
#include <string.h>
#include <stdlib.h>

#include "internal.h"

/* A 1 m square of 32 x 32 points, 0.01 kg each (spacing 1/31 m). Hanging
 * from one edge, the top stretch spring carries about 31 * 0.01 * 9.81 = 3 N:
 * k_stretch = 1000 N/m stretches it by 3 mm, 9% of the spacing, inside
 * Provot's usual 5-10%. The paper's period pi * sqrt(m / k) is then 10 ms
 * (the grid's fastest mode allows steps up to about 3 ms), so a 1 ms step
 * is safe. Cloth resists shear less and bending least: 10x, 100x softer. */
void msocl_cloth_desc_init(msocl_cloth_desc *d) {
  int c;

  if (!d) return;
  d->nx = d->ny = 32;
  for (c = 0; c < 3; c++) d->origin[c] = d->u[c] = d->v[c] = 0.0f;
  d->u[0] = 1.0f;
  d->v[2] = 1.0f;
  d->point_mass = 0.01f;
  d->k_stretch = 1000.0f;
  d->k_shear = 100.0f;
  d->k_bend = 10.0f;
  d->damping = 0.0f;
}


/* u and v span the cloth: neither zero nor parallel (the cross product is
 * tiny against the lengths), else the triangles have no area. */
static int check_axes(const float *u, const float *v) {
  double cx = (double)u[1] * v[2] - (double)u[2] * v[1];
  double cy = (double)u[2] * v[0] - (double)u[0] * v[2];
  double cz = (double)u[0] * v[1] - (double)u[1] * v[0];
  double lu =
      sqrt((double)u[0] * u[0] + (double)u[1] * u[1] + (double)u[2] * u[2]);
  double lv =
      sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);

  if (lu == 0 || lv == 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "cloth: %s axis is zero",
                       lu == 0 ? "u" : "v");
  if (sqrt(cx * cx + cy * cy + cz * cz) <= 1e-6 * lu * lv)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "cloth: u (%g, %g, %g) and v (%g, %g, %g) are parallel",
                       u[0], u[1], u[2], v[0], v[1], v[2]);
  return MSOCL_OK;
}

/* Springs of a full grid: stretch, shear, bend. */
static long long all_springs(long long nx, long long ny) {
  return (nx - 1) * ny + nx * (ny - 1) + 2 * (nx - 1) * (ny - 1) +
         (nx - 2) * ny + nx * (ny - 2);
}

static int check_desc(const msocl_cloth_desc *d) {
  int rc;

  if (d->nx < 2 || d->ny < 2)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "cloth: %d x %d points, need at least 2 x 2", d->nx,
                       d->ny);
  /* The model's own limits, checked here before the scratch arrays are
   * sized: 3 floats per point, 2 ints per spring and 3 per triangle must
   * index with an int. */
  if ((long long)d->nx * d->ny > INT_MAX / 3 ||
      all_springs(d->nx, d->ny) > INT_MAX / 2 ||
      2LL * (d->nx - 1) * (d->ny - 1) > INT_MAX / 3)
    return msocl__fail(MSOCL_ERR_TOO_MANY, "cloth: %d x %d points is too many",
                       d->nx, d->ny);
  if ((rc = msocl__check_finite("cloth", "origin", d->origin, 3)) ||
      (rc = msocl__check_finite("cloth", "u", d->u, 3)) || (rc = msocl__check_finite("cloth", "v", d->v, 3)) ||
      (rc = msocl__check_finite("cloth", "point_mass", &d->point_mass, 1)) ||
      (rc = msocl__check_finite("cloth", "k_stretch", &d->k_stretch, 1)) ||
      (rc = msocl__check_finite("cloth", "k_shear", &d->k_shear, 1)) ||
      (rc = msocl__check_finite("cloth", "k_bend", &d->k_bend, 1)) ||
      (rc = msocl__check_finite("cloth", "damping", &d->damping, 1)))
    return rc;
  if (!(d->point_mass > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS, "cloth: point mass %g must be > 0",
                       d->point_mass);
  if ((rc = msocl__check_coef("cloth", "k_stretch", d->k_stretch)) ||
      (rc = msocl__check_coef("cloth", "k_shear", d->k_shear)) ||
      (rc = msocl__check_coef("cloth", "k_bend", d->k_bend)) ||
      (rc = msocl__check_coef("cloth", "damping", d->damping)))
    return rc;
  return check_axes(d->u, d->v);
}

/* Scratch arrays for one add_springs call, in the documented order. */
struct springs {
  int n, *ij;
  float *k, *rest;
  const float *rests; /* the six per-kind rest lengths, as in the model */
};

static void push(struct springs *s, int a, int b, float k, int kind) {
  s->ij[2 * s->n] = a;
  s->ij[2 * s->n + 1] = b;
  s->rest[s->n] = s->rests[kind];
  s->k[s->n++] = k;
}

/* Rest lengths by kind, from the grid's geometry in double: every spring of
 * a kind rests at the same length (not each at its rounded distance), so
 * the GRID layout, which stores none, sums bit for bit what the others do:
 * stretch along u, v; shear u+v, v-u; bend along u, v. */
static void kind_rests(const msocl_cloth_desc *d, float *rest) {
  double du[3], dv[3], len[4] = {0, 0, 0, 0};
  for (int c = 0; c < 3; c++) {
    du[c] = (double)d->u[c] / (d->nx - 1);
    dv[c] = (double)d->v[c] / (d->ny - 1);
    len[0] += du[c] * du[c];
    len[1] += dv[c] * dv[c];
    len[2] += (du[c] + dv[c]) * (du[c] + dv[c]);
    len[3] += (dv[c] - du[c]) * (dv[c] - du[c]);
  }
  for (int q = 0; q < 4; q++)
    rest[q] = (float)sqrt(len[q]);
  rest[4] = (float)(2.0 * sqrt(len[0]));
  rest[5] = (float)(2.0 * sqrt(len[1]));
}

static void push_springs(struct springs *s, const msocl_cloth_desc *d) {
  int i, j, nx = d->nx, ny = d->ny;

  if (d->k_stretch > 0)
    for (j = 0; j < ny; j++)
      for (i = 0; i < nx; i++) {
        if (i + 1 < nx) push(s, j * nx + i, j * nx + i + 1, d->k_stretch, 0);
        if (j + 1 < ny) push(s, j * nx + i, (j + 1) * nx + i, d->k_stretch, 1);
      }
  if (d->k_shear > 0)
    for (j = 0; j + 1 < ny; j++)
      for (i = 0; i + 1 < nx; i++) {
        push(s, j * nx + i, (j + 1) * nx + i + 1, d->k_shear, 2);
        push(s, j * nx + i + 1, (j + 1) * nx + i, d->k_shear, 3);
      }
  if (d->k_bend > 0)
    for (j = 0; j < ny; j++)
      for (i = 0; i < nx; i++) {
        if (i + 2 < nx) push(s, j * nx + i, j * nx + i + 2, d->k_bend, 4);
        if (j + 2 < ny) push(s, j * nx + i, (j + 2) * nx + i, d->k_bend, 5);
      }
}

/* Points at origin + i/(nx-1) u + j/(ny-1) v, computed in double. */
static int add_points(msocl_model *m, const msocl_cloth_desc *d) {
  int i, j, c, n = d->nx * d->ny, rc;
  float *xyz = malloc((size_t)n * 3 * sizeof *xyz);
  float *mass = malloc((size_t)n * sizeof *mass);

  if (!xyz || !mass) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "cloth: cannot allocate %d points",
                     n);
  } else {
    for (j = 0; j < d->ny; j++)
      for (i = 0; i < d->nx; i++) {
        double a = (double)i / (d->nx - 1), b = (double)j / (d->ny - 1);
        for (c = 0; c < 3; c++)
          xyz[3 * (j * d->nx + i) + c] =
              (float)(d->origin[c] + a * d->u[c] + b * d->v[c]);
        mass[j * d->nx + i] = d->point_mass;
      }
    rc = msocl_model_add_points(m, n, xyz, mass, NULL);
  }
  free(xyz);
  free(mass);
  return rc;
}

static int add_springs(msocl_model *m, const msocl_cloth_desc *d) {
  long long most = all_springs(d->nx, d->ny);
  float rests[6];
  kind_rests(d, rests);
  struct springs s = {0, NULL, NULL, NULL, rests};
  float *damp = NULL;
  int i, rc = MSOCL_OK;

  s.ij = malloc((size_t)most * 2 * sizeof *s.ij);
  s.k = malloc((size_t)most * sizeof *s.k);
  s.rest = malloc((size_t)most * sizeof *s.rest);
  if (d->damping > 0) damp = malloc((size_t)most * sizeof *damp);
  if (!s.ij || !s.k || !s.rest || (d->damping > 0 && !damp)) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "cloth: cannot allocate %lld springs",
                     most);
  } else {
    push_springs(&s, d);
    for (i = 0; damp && i < s.n; i++) damp[i] = d->damping;
    if (s.n > 0) rc = msocl_model_add_springs(m, s.n, s.ij, s.k, s.rest, damp);
  }
  if (rc == MSOCL_OK) {
    m->grid.nx = d->nx;
    m->grid.ny = d->ny;
    m->grid.ns = m->ns;
    m->grid.k[0] = d->k_stretch;
    m->grid.k[1] = d->k_shear;
    m->grid.k[2] = d->k_bend;
    memcpy(m->grid.rest, rests, sizeof rests);
    m->grid.damp = d->damping;
  }
  free(s.ij);
  free(s.k);
  free(s.rest);
  free(damp);
  return rc;
}

/* Two triangles per quad, both wound (i, j) -> +u -> +v, so every normal
 * points along u x v. */
static int add_triangles(msocl_model *m, const msocl_cloth_desc *d) {
  int i, j, t = 0, nx = d->nx, n = 2 * (d->nx - 1) * (d->ny - 1), rc;
  int *ijk = malloc((size_t)n * 3 * sizeof *ijk);

  if (!ijk)
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "cloth: cannot allocate %d triangles", n);
  for (j = 0; j + 1 < d->ny; j++)
    for (i = 0; i + 1 < nx; i++) {
      int p = j * nx + i;
      ijk[t++] = p;
      ijk[t++] = p + 1;
      ijk[t++] = p + nx + 1;
      ijk[t++] = p;
      ijk[t++] = p + nx + 1;
      ijk[t++] = p + nx;
    }
  rc = msocl_model_add_triangles(m, n, ijk);
  free(ijk);
  return rc;
}

int msocl_model_cloth_grid(msocl_model **m, const msocl_cloth_desc *d) {
  int rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!d)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "cloth description is NULL");
  if ((rc = check_desc(d)) || (rc = msocl_model_create(m))) return rc;
  /* validate: the combinations of the model's limits (msocl.h) */
  if ((rc = add_points(*m, d)) || (rc = add_springs(*m, d)) ||
      (rc = add_triangles(*m, d)) || (rc = msocl_model_validate(*m))) {
    msocl_model_destroy(*m);
    *m = NULL;
  }
  return rc;
}
