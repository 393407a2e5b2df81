/* Deformable solids after Vassilev & Spanlang: springs along the edges of a
 * closed surface plus support springs from every surface point to a centre
 * point, on an icosphere or on a user's closed mesh. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "internal.h"

#define MAX_SUBDIVISIONS 7

/* A ball of radius 0.1 m, 162 surface points of 0.2 / 162 = 1.2 g and a
 * 20 g centre, its centre 0.3 m above y = 0. Gershgorin bounds the fastest
 * mode: a surface point has at most 6 edges and one support spring,
 * w^2 <= 4 (6 * 200 + 100) / 0.00123 = 4.2e6 (w = 2052 rad/s), the centre
 * 162 support springs, w^2 <= 4 * 162 * 100 / 0.02 = 3.2e6; symplectic
 * Euler needs dt * w < 2, and dt = 1e-4 s gives 0.21. The dashpots damp at
 * a rate of at most 2 * 162 * 0.05 / 0.02 = 810/s (the centre); with it
 * the bound is (dt w)^2 + 2 dt rate < 4, here 0.2. */
void msocl_solid_desc_init(msocl_solid_desc *d) {
  int c;

  if (!d) return;
  d->subdivisions = 2;
  for (c = 0; c < 3; c++) {
    d->centre[c] = 0.0f;
    d->radii[c] = 0.1f;
  }
  d->centre[1] = 0.3f;
  d->surface_mass = 0.2f;
  d->centre_mass = 0.02f;
  d->k_surface = 200.0f;
  d->k_support = 100.0f;
  d->damping = 0.05f;
}

/* ---------------------------------------------------------------- checks */


/* The fields both builders use: masses, stiffnesses, damping. */
static int check_material(const msocl_solid_desc *d) {
  int rc;

  if ((rc = msocl__check_finite("solid", "surface_mass", &d->surface_mass, 1)) ||
      (rc = msocl__check_finite("solid", "centre_mass", &d->centre_mass, 1)) ||
      (rc = msocl__check_finite("solid", "k_surface", &d->k_surface, 1)) ||
      (rc = msocl__check_finite("solid", "k_support", &d->k_support, 1)) ||
      (rc = msocl__check_finite("solid", "damping", &d->damping, 1)))
    return rc;
  if (!(d->surface_mass > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS,
                       "solid: surface mass %g must be > 0", d->surface_mass);
  if (!(d->centre_mass > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS, "solid: centre mass %g must be > 0",
                       d->centre_mass);
  if ((rc = msocl__check_coef("solid", "k_surface", d->k_surface)) ||
      (rc = msocl__check_coef("solid", "k_support", d->k_support)) ||
      (rc = msocl__check_coef("solid", "damping", d->damping)))
    return rc;
  return MSOCL_OK;
}

static int check_shape(const msocl_solid_desc *d) {
  int c, rc;

  if (d->subdivisions < 0 || d->subdivisions > MAX_SUBDIVISIONS)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "solid: %d subdivisions, need 0 to %d", d->subdivisions,
                       MAX_SUBDIVISIONS);
  if ((rc = msocl__check_finite("solid", "centre", d->centre, 3)) ||
      (rc = msocl__check_finite("solid", "radii", d->radii, 3)))
    return rc;
  for (c = 0; c < 3; c++)
    if (!(d->radii[c] > 0))
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "solid: radii[%d] = %g must be > 0", c, d->radii[c]);
  return MSOCL_OK;
}

/* ------------------------------------------------------------- edge map */

/* Open addressing over undirected edges (a < b, so key 0 is never an
 * edge and marks an empty slot). */
struct edge_map {
  size_t mask;
  int bits; /* mask = 2^bits - 1 */
  uint64_t *key;
  int *val, *fwd, *bwd;
};

static int edge_map_init(struct edge_map *e, size_t edges) {
  size_t cap = 16;
  e->bits = 4;
  while (cap < 2 * edges) {
    cap *= 2;
    e->bits++;
  }
  e->mask = cap - 1;
  e->key = calloc(cap, sizeof *e->key);
  e->val = malloc(cap * sizeof *e->val);
  e->fwd = calloc(cap, sizeof *e->fwd);
  e->bwd = calloc(cap, sizeof *e->bwd);
  if (!e->key || !e->val || !e->fwd || !e->bwd)
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "solid: cannot allocate a map of %zu edges", edges);
  return MSOCL_OK;
}

static void edge_map_free(struct edge_map *e) {
  free(e->key);
  free(e->val);
  free(e->fwd);
  free(e->bwd);
}

/* The slot of edge {a, b}, claimed (val -1) if new; *fresh says which. */
static size_t edge_slot(struct edge_map *e, int a, int b, int *fresh) {
  uint64_t k;
  size_t h;

  if (a > b) {
    int t = a;
    a = b;
    b = t;
  }
  k = (uint64_t)a << 32 | (uint32_t)b;
  /* Fibonacci hashing: the top bits of the product. */
  h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> (64 - e->bits));
  while (e->key[h] && e->key[h] != k) h = (h + 1) & e->mask;
  *fresh = !e->key[h];
  if (*fresh) {
    e->key[h] = k;
    e->val[h] = -1;
  }
  return h;
}

/* -------------------------------------------------------------- icosphere */

struct mesh {
  int np, nt;
  double *p; /* 3 np */
  int *t;    /* 3 nt */
};

/* The midpoint of edge {a, b}, projected onto the unit sphere; made once
 * and shared by the edge's two triangles. */
static int midpoint(struct mesh *m, struct edge_map *e, int a, int b) {
  int fresh, c;
  size_t h = edge_slot(e, a, b, &fresh);
  double q[3], len = 0;

  if (!fresh) return e->val[h];
  for (c = 0; c < 3; c++) {
    q[c] = 0.5 * (m->p[3 * a + c] + m->p[3 * b + c]);
    len += q[c] * q[c];
  }
  len = sqrt(len);
  for (c = 0; c < 3; c++) m->p[3 * m->np + c] = q[c] / len;
  return e->val[h] = m->np++;
}

/* Splits every triangle into four (corner, midpoints) keeping its winding. */
static int subdivide(struct mesh *m, int *next) {
  struct edge_map e;
  int t, c, *out = next, rc;

  if ((rc = edge_map_init(&e, 3 * (size_t)m->nt / 2)) == MSOCL_OK) {
    for (t = 0; t < m->nt; t++) {
      const int *v = m->t + 3 * t;
      int ab = midpoint(m, &e, v[0], v[1]);
      int bc = midpoint(m, &e, v[1], v[2]);
      int ca = midpoint(m, &e, v[2], v[0]);
      const int four[12] = {v[0], ab, ca, ab, v[1], bc, ca, bc, v[2],
                            ab, bc, ca};
      for (c = 0; c < 12; c++) *out++ = four[c];
    }
    m->nt *= 4;
  }
  edge_map_free(&e);
  return rc;
}

/* The unit icosphere: the 12-vertex icosahedron (vertices (0, +-1, +-g)
 * and their cyclic shifts, g the golden ratio), subdivided s times: 10 * 4^s
 * + 2 points, 20 * 4^s triangles wound counter-clockwise seen from
 * outside. */
static int icosphere(struct mesh *m, int s) {
  static const double ico[12][3] = {
      {-1, 1.618033988749895, 0}, {1, 1.618033988749895, 0},
      {-1, -1.618033988749895, 0}, {1, -1.618033988749895, 0},
      {0, -1, 1.618033988749895}, {0, 1, 1.618033988749895},
      {0, -1, -1.618033988749895}, {0, 1, -1.618033988749895},
      {1.618033988749895, 0, -1}, {1.618033988749895, 0, 1},
      {-1.618033988749895, 0, -1}, {-1.618033988749895, 0, 1}};
  static const int faces[20][3] = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  size_t np = 10 * ((size_t)1 << 2 * s) + 2, nt = 20 * ((size_t)1 << 2 * s);
  int i, c, level, *next;
  const double len = sqrt(1 + 1.618033988749895 * 1.618033988749895);

  m->p = malloc(np * 3 * sizeof *m->p);
  m->t = malloc(nt * 3 * sizeof *m->t);
  next = malloc(nt * 3 * sizeof *next);
  if (!m->p || !m->t || !next) {
    free(next);
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "solid: cannot allocate an icosphere of %zu points",
                       np);
  }
  m->np = 12;
  m->nt = 20;
  for (i = 0; i < 12; i++)
    for (c = 0; c < 3; c++) m->p[3 * i + c] = ico[i][c] / len;
  for (i = 0; i < 20; i++)
    for (c = 0; c < 3; c++) m->t[3 * i + c] = faces[i][c];
  for (level = 0; level < s; level++) {
    int rc = subdivide(m, next), *swap = m->t;
    if (rc) {
      free(next);
      return rc;
    }
    m->t = next;
    next = swap;
  }
  free(next);
  return MSOCL_OK;
}

/* ---------------------------------------------------------------- builder */

/* Points (surface, then the centre), springs (every edge once, in the
 * order triangles first use it; then a support spring from each surface
 * point to the centre), triangles. A closed, consistently wound mesh uses
 * each edge once in each direction, so "a < b" picks it exactly once. */
static int build(msocl_model **out, int np, const float *xyz, int nt,
                 const int *ijk, const double centre[3],
                 const msocl_solid_desc *d) {
  int n = np + 1, ns = 3 * nt / 2 + np, i, c, s = 0, rc;
  float *pos = malloc((size_t)n * 3 * sizeof *pos);
  float *mass = malloc((size_t)n * sizeof *mass);
  int *ij = malloc((size_t)ns * 2 * sizeof *ij);
  float *k = malloc((size_t)ns * sizeof *k);
  float *damp = d->damping > 0 ? malloc((size_t)ns * sizeof *damp) : NULL;
  msocl_model *m = NULL;

  if (!pos || !mass || !ij || !k || (d->damping > 0 && !damp)) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY,
                     "solid: cannot allocate %d points and %d springs", n, ns);
    goto out;
  }
  for (i = 0; i < 3 * np; i++) pos[i] = xyz[i];
  for (c = 0; c < 3; c++) pos[3 * np + c] = (float)centre[c];
  for (i = 0; i < np; i++) mass[i] = (float)((double)d->surface_mass / np);
  mass[np] = d->centre_mass;
  for (i = 0; i < 3 * nt; i++) {
    int a = ijk[i], b = ijk[i % 3 == 2 ? i - 2 : i + 1];
    if (a < b) {
      ij[2 * s] = a;
      ij[2 * s + 1] = b;
      k[s++] = d->k_surface;
    }
  }
  for (i = 0; i < np; i++) {
    ij[2 * s] = i;
    ij[2 * s + 1] = np;
    k[s++] = d->k_support;
  }
  for (i = 0; damp && i < ns; i++) damp[i] = d->damping;
  /* A stiffness of 0 leaves that set out, as the other builders do. */
  if ((rc = msocl_model_create(&m)) ||
      (rc = msocl_model_add_points(m, n, pos, mass, NULL)))
    goto out;
  if (d->k_surface > 0 && d->k_support > 0)
    rc = msocl_model_add_springs(m, ns, ij, k, NULL, damp);
  else if (d->k_surface > 0)
    rc = msocl_model_add_springs(m, ns - np, ij, k, NULL, damp);
  else if (d->k_support > 0)
    rc = msocl_model_add_springs(m, np, ij + 2 * (ns - np), k + ns - np, NULL,
                                 damp);
  if (rc == MSOCL_OK) rc = msocl_model_add_triangles(m, nt, ijk);
  /* the combinations of the model's limits (msocl.h) */
  if (rc == MSOCL_OK) rc = msocl_model_validate(m);
out:
  if (rc) {
    msocl_model_destroy(m);
    m = NULL;
  }
  *out = m;
  free(pos);
  free(mass);
  free(ij);
  free(k);
  free(damp);
  return rc;
}

int msocl_model_solid(msocl_model **m, const msocl_solid_desc *d) {
  struct mesh sph = {0, 0, NULL, NULL};
  float *xyz = NULL;
  double centre[3];
  int i, c, rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!d)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "solid description is NULL");
  if ((rc = check_shape(d)) || (rc = check_material(d))) return rc;
  if ((rc = icosphere(&sph, d->subdivisions)) == MSOCL_OK) {
    if (!(xyz = malloc((size_t)sph.np * 3 * sizeof *xyz))) {
      rc = msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "solid: cannot allocate %d points", sph.np);
    } else {
      for (c = 0; c < 3; c++) centre[c] = d->centre[c];
      for (i = 0; i < sph.np; i++)
        for (c = 0; c < 3; c++)
          xyz[3 * i + c] =
              (float)(centre[c] + (double)d->radii[c] * sph.p[3 * i + c]);
      rc = build(m, sph.np, xyz, sph.nt, sph.t, centre, d);
    }
  }
  free(xyz);
  free(sph.p);
  free(sph.t);
  return rc;
}

/* ------------------------------------------------------------ user mesh */

/* Corners in range and distinct, coordinates finite. */
static int check_elements(int np, const float *xyz, int nt, const int *ijk) {
  int i, c;

  for (i = 0; i < 3 * np; i++)
    if (!isfinite(xyz[i]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "solid: point %d: %c = %g is not finite", i / 3,
                         "xyz"[i % 3], xyz[i]);
  for (i = 0; i < nt; i++) {
    const int *v = ijk + 3 * i;
    for (c = 0; c < 3; c++)
      if (v[c] < 0 || v[c] >= np)
        return msocl__fail(MSOCL_ERR_BAD_INDEX,
                           "solid: triangle %d: point index %d out of range "
                           "[0, %d)",
                           i, v[c], np);
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "solid: triangle %d: corners (%d, %d, %d) are not "
                         "distinct",
                         i, v[0], v[1], v[2]);
  }
  return MSOCL_OK;
}

/* A closed surface has every edge in exactly two triangles; wound
 * consistently, they run it in opposite directions. */
static int check_closed(int nt, const int *ijk) {
  struct edge_map e;
  int i, fresh, rc;
  size_t h;

  if ((rc = edge_map_init(&e, 3 * (size_t)nt)) == MSOCL_OK) {
    for (i = 0; i < 3 * nt; i++) {
      int a = ijk[i], b = ijk[i % 3 == 2 ? i - 2 : i + 1];
      h = edge_slot(&e, a, b, &fresh);
      if (fresh) e.val[h] = i / 3; /* the first triangle to use it */
      if (a < b)
        e.fwd[h]++;
      else
        e.bwd[h]++;
    }
    for (h = 0; h <= e.mask && rc == MSOCL_OK; h++) {
      int a = (int)(e.key[h] >> 32), b = (int)(e.key[h] & 0xffffffffu);
      if (!e.key[h]) continue;
      if (e.fwd[h] + e.bwd[h] != 2)
        rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "solid: edge (%d, %d) belongs to %d triangle%s "
                         "(first: triangle %d), not 2: the mesh is not closed",
                         a, b, e.fwd[h] + e.bwd[h],
                         e.fwd[h] + e.bwd[h] == 1 ? "" : "s", e.val[h]);
      else if (e.fwd[h] != 1)
        rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "solid: edge (%d, %d) runs the same way in both its "
                         "triangles (first: triangle %d): the mesh is not "
                         "consistently wound",
                         a, b, e.val[h]);
    }
  }
  edge_map_free(&e);
  return rc;
}

int msocl_model_solid_from_mesh(msocl_model **m, int npoints, const float *xyz,
                                int ntri, const int *ijk,
                                const msocl_solid_desc *d) {
  double centre[3] = {0, 0, 0};
  int i, rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!xyz || !ijk || !d)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "solid: points, triangles or description is NULL");
  /* The smallest closed surface is a tetrahedron. */
  if (npoints < 4 || ntri < 4)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "solid: %d points, %d triangles; a closed mesh needs "
                       "at least 4 of each",
                       npoints, ntri);
  /* Room for the centre point, 3 indices per triangle, and the springs
   * (3/2 per triangle plus one per point) at 2 indices each. */
  if (npoints > INT_MAX / 3 - 1 || ntri > INT_MAX / 3 ||
      3LL * ntri / 2 + npoints > INT_MAX / 2)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "solid: %d points, %d triangles is too many", npoints,
                       ntri);
  if ((rc = check_material(d)) ||
      (rc = check_elements(npoints, xyz, ntri, ijk)) ||
      (rc = check_closed(ntri, ijk)))
    return rc;
  for (i = 0; i < 3 * npoints; i++) centre[i % 3] += xyz[i];
  for (i = 0; i < 3; i++) centre[i] /= npoints;
  return build(m, npoints, xyz, ntri, ijk, centre, d);
}
