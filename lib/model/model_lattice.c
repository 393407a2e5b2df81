/* A 3D lattice of points ("jello cube") with structural, face shear, body
 * shear and bend springs and an outward-wound surface, built through the
 * public model calls. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* An 8 x 8 x 8 cube of 2 g points, 2 cm apart (14 cm a side, 1 kg), centred
 * on the y axis with its bottom 10 cm above y = 0. An inner point carries
 * 6 structural, 12 face shear and 6 bend springs, so Gershgorin bounds the
 * fastest mode by w^2 <= 4 (6 * 200 + 12 * 100 + 6 * 50) / 0.002 = 5.4e6,
 * w = 2324 rad/s: symplectic Euler needs dt * w < 2, and dt = 1e-4 s gives
 * 0.23. The dashpots (24 x 0.02 N s/m) damp at a rate of at most
 * 2 * 24 * 0.02 / 0.002 = 480/s; with it the bound is (dt w)^2 + 2 dt rate
 * < 4, here 0.15. Resting on its bottom face, a column of 8 points squeezes
 * its lowest structural spring by 8 * 0.002 * 9.81 / 200 = 0.8 mm, 4% of
 * the spacing: firm, yet it wobbles. */
void msocl_lattice_desc_init(msocl_lattice_desc *d) {
  if (!d) return;
  d->nx = d->ny = d->nz = 8;
  d->spacing = 0.02f;
  d->origin[0] = d->origin[2] = -0.07f;
  d->origin[1] = 0.1f;
  d->point_mass = 0.002f;
  d->k_structural = 200.0f;
  d->k_shear_face = 100.0f;
  d->k_shear_body = 0.0f;
  d->k_bend = 50.0f;
  d->damping = 0.02f;
}


/* Springs of each set in a full lattice (see the header's counts). */
static long long structural(long long x, long long y, long long z) {
  return (x - 1) * y * z + x * (y - 1) * z + x * y * (z - 1);
}
static long long shear_face(long long x, long long y, long long z) {
  return 2 * ((x - 1) * (y - 1) * z + (x - 1) * y * (z - 1) +
              x * (y - 1) * (z - 1));
}
static long long shear_body(long long x, long long y, long long z) {
  return 4 * (x - 1) * (y - 1) * (z - 1);
}
static long long bend(long long x, long long y, long long z) {
  return (x - 2) * y * z + x * (y - 2) * z + x * y * (z - 2);
}

/* The springs of the enabled sets. */
static long long spring_count(const msocl_lattice_desc *d) {
  long long x = d->nx, y = d->ny, z = d->nz, n = 0;
  if (d->k_structural > 0) n += structural(x, y, z);
  if (d->k_shear_face > 0) n += shear_face(x, y, z);
  if (d->k_shear_body > 0) n += shear_body(x, y, z);
  if (d->k_bend > 0) n += bend(x, y, z);
  return n;
}

/* Two per boundary square of the six faces. */
static long long triangle_count(long long x, long long y, long long z) {
  return 4 * ((x - 1) * (y - 1) + (x - 1) * (z - 1) + (y - 1) * (z - 1));
}

static int check_desc(const msocl_lattice_desc *d) {
  int rc;

  if (d->nx < 2 || d->ny < 2 || d->nz < 2)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "lattice: %d x %d x %d points, need at least 2 x 2 x 2",
                       d->nx, d->ny, d->nz);
  if ((rc = msocl__check_finite("lattice", "origin", d->origin, 3)) ||
      (rc = msocl__check_finite("lattice", "spacing", &d->spacing, 1)) ||
      (rc = msocl__check_finite("lattice", "point_mass", &d->point_mass, 1)) ||
      (rc = msocl__check_finite("lattice", "k_structural", &d->k_structural, 1)) ||
      (rc = msocl__check_finite("lattice", "k_shear_face", &d->k_shear_face, 1)) ||
      (rc = msocl__check_finite("lattice", "k_shear_body", &d->k_shear_body, 1)) ||
      (rc = msocl__check_finite("lattice", "k_bend", &d->k_bend, 1)) ||
      (rc = msocl__check_finite("lattice", "damping", &d->damping, 1)))
    return rc;
  if (!(d->spacing > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "lattice: spacing %g must be > 0",
                       d->spacing);
  if (!(d->point_mass > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS,
                       "lattice: point mass %g must be > 0", d->point_mass);
  if ((rc = msocl__check_coef("lattice", "k_structural", d->k_structural)) ||
      (rc = msocl__check_coef("lattice", "k_shear_face", d->k_shear_face)) ||
      (rc = msocl__check_coef("lattice", "k_shear_body", d->k_shear_body)) ||
      (rc = msocl__check_coef("lattice", "k_bend", d->k_bend)) ||
      (rc = msocl__check_coef("lattice", "damping", d->damping)))
    return rc;
  /* The model's own limits, checked before the scratch arrays are sized:
   * 3 floats per point, 2 ints per spring and 3 per triangle must index
   * with an int. nx * ny is checked first so the triple product cannot
   * overflow a long long. */
  if ((long long)d->nx * d->ny > INT_MAX / 3 ||
      (long long)d->nx * d->ny * d->nz > INT_MAX / 3 ||
      spring_count(d) > INT_MAX / 2 ||
      triangle_count(d->nx, d->ny, d->nz) > INT_MAX / 3)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "lattice: %d x %d x %d points is too many", d->nx,
                       d->ny, d->nz);
  return MSOCL_OK;
}

/* Scratch arrays for one add_springs call, in the documented order. */
struct springs {
  int n, *ij;
  float *k, *rest;
  const float *rests; /* by kind: structural, face, body, bend */
};

static void push(struct springs *s, int a, int b, float k, int kind) {
  s->ij[2 * s->n] = a;
  s->ij[2 * s->n + 1] = b;
  s->rest[s->n] = s->rests[kind];
  s->k[s->n++] = k;
}

/* Rest lengths by kind, from the spacing in double: every spring of a kind
 * rests at the same length (not each at its rounded distance), so the GRID
 * layout, which stores none, sums bit for bit what the others do. */
static void kind_rests(const msocl_lattice_desc *d, float *rest) {
  const double h = d->spacing;
  rest[0] = (float)h;
  rest[1] = (float)(h * sqrt(2.0));
  rest[2] = (float)(h * sqrt(3.0));
  rest[3] = (float)(2.0 * h);
}

/* Each set loops k, then j, then i (the index order), so a set's springs
 * run through the lattice in point order (kernels/common.h's 3-D GRID
 * tables list a point's neighbours in the order this gives them). */
static void push_springs(struct springs *s, const msocl_lattice_desc *d) {
  int i, j, k, nx = d->nx, ny = d->ny, nz = d->nz;
  int dx = 1, dy = nx, dz = nx * ny;
#define FOR_POINTS                                                            \
  for (k = 0; k < nz; k++)                                                    \
    for (j = 0; j < ny; j++)                                                  \
      for (i = 0; i < nx; i++)
#define P ((k * ny + j) * nx + i)

  if (d->k_structural > 0)
    FOR_POINTS {
      if (i + 1 < nx) push(s, P, P + dx, d->k_structural, 0);
      if (j + 1 < ny) push(s, P, P + dy, d->k_structural, 0);
      if (k + 1 < nz) push(s, P, P + dz, d->k_structural, 0);
    }
  /* Both diagonals of the square whose lowest corner is P, in the xy, xz
   * and yz planes. */
  if (d->k_shear_face > 0)
    FOR_POINTS {
      if (i + 1 < nx && j + 1 < ny) {
        push(s, P, P + dx + dy, d->k_shear_face, 1);
        push(s, P + dx, P + dy, d->k_shear_face, 1);
      }
      if (i + 1 < nx && k + 1 < nz) {
        push(s, P, P + dx + dz, d->k_shear_face, 1);
        push(s, P + dx, P + dz, d->k_shear_face, 1);
      }
      if (j + 1 < ny && k + 1 < nz) {
        push(s, P, P + dy + dz, d->k_shear_face, 1);
        push(s, P + dy, P + dz, d->k_shear_face, 1);
      }
    }
  /* The four body diagonals of the cell whose lowest corner is P. */
  if (d->k_shear_body > 0)
    FOR_POINTS {
      if (i + 1 < nx && j + 1 < ny && k + 1 < nz) {
        push(s, P, P + dx + dy + dz, d->k_shear_body, 2);
        push(s, P + dx, P + dy + dz, d->k_shear_body, 2);
        push(s, P + dy, P + dx + dz, d->k_shear_body, 2);
        push(s, P + dz, P + dx + dy, d->k_shear_body, 2);
      }
    }
  if (d->k_bend > 0)
    FOR_POINTS {
      if (i + 2 < nx) push(s, P, P + 2 * dx, d->k_bend, 3);
      if (j + 2 < ny) push(s, P, P + 2 * dy, d->k_bend, 3);
      if (k + 2 < nz) push(s, P, P + 2 * dz, d->k_bend, 3);
    }
#undef FOR_POINTS
#undef P
}

/* Points at origin + spacing * (i, j, k), computed in double. */
static int add_points(msocl_model *m, const msocl_lattice_desc *d) {
  int i, j, k, n = d->nx * d->ny * d->nz, p = 0, rc;
  float *xyz = malloc((size_t)n * 3 * sizeof *xyz);
  float *mass = malloc((size_t)n * sizeof *mass);

  if (!xyz || !mass) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY,
                     "lattice: cannot allocate %d points", n);
  } else {
    for (k = 0; k < d->nz; k++)
      for (j = 0; j < d->ny; j++)
        for (i = 0; i < d->nx; i++, p++) {
          xyz[3 * p] = (float)(d->origin[0] + (double)d->spacing * i);
          xyz[3 * p + 1] = (float)(d->origin[1] + (double)d->spacing * j);
          xyz[3 * p + 2] = (float)(d->origin[2] + (double)d->spacing * k);
          mass[p] = d->point_mass;
        }
    rc = msocl_model_add_points(m, n, xyz, mass, NULL);
  }
  free(xyz);
  free(mass);
  return rc;
}

static int add_springs(msocl_model *m, const msocl_lattice_desc *d) {
  long long most = spring_count(d);
  float rests[4];
  kind_rests(d, rests);
  struct springs s = {0, NULL, NULL, NULL, rests};
  float *damp = NULL;
  int i, rc = MSOCL_OK;

  if (most > 0) {
    s.ij = malloc((size_t)most * 2 * sizeof *s.ij);
    s.k = malloc((size_t)most * sizeof *s.k);
    s.rest = malloc((size_t)most * sizeof *s.rest);
    if (d->damping > 0) damp = malloc((size_t)most * sizeof *damp);
    if (!s.ij || !s.k || !s.rest || (d->damping > 0 && !damp)) {
      rc = msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "lattice: cannot allocate %lld springs", most);
    } else {
      push_springs(&s, d);
      for (i = 0; damp && i < s.n; i++) damp[i] = d->damping;
      if (s.n > 0)
        rc = msocl_model_add_springs(m, s.n, s.ij, s.k, s.rest, damp);
    }
  }
  if (rc == MSOCL_OK) { /* the record the GRID layout works from */
    const float k[4] = {d->k_structural, d->k_shear_face, d->k_shear_body,
                        d->k_bend};
    m->grid.nx = d->nx;
    m->grid.ny = d->ny;
    m->grid.nz = d->nz;
    m->grid.ns = m->ns;
    memcpy(m->grid.k, k, sizeof k);
    memcpy(m->grid.rest, rests, sizeof rests);
    m->grid.damp = d->damping > 0 ? d->damping : 0.0f;
  }
  free(s.ij);
  free(s.k);
  free(s.rest);
  free(damp);
  return rc;
}

/* The squares of one boundary face: points with coordinate `axis` at its
 * low (side 0) or high end, spanned by axes a and b chosen so that a x b
 * is the outward normal; each square (p, p + a, p + a + b, p + b) becomes
 * two triangles wound a -> b. */
static int *face(int *t, const int n[3], int axis, int side, int a, int b) {
  int c[3], u, v;
  const int step[3] = {1, n[0], n[0] * n[1]};

  c[axis] = side ? n[axis] - 1 : 0;
  for (v = 0; v + 1 < n[b]; v++)
    for (u = 0; u + 1 < n[a]; u++) {
      int p;
      c[a] = u;
      c[b] = v;
      p = (c[2] * n[1] + c[1]) * n[0] + c[0];
      *t++ = p;
      *t++ = p + step[a];
      *t++ = p + step[a] + step[b];
      *t++ = p;
      *t++ = p + step[a] + step[b];
      *t++ = p + step[b];
    }
  return t;
}

static int add_triangles(msocl_model *m, const msocl_lattice_desc *d) {
  /* axis, side, a, b, with a x b outward: y x = -z, x y = z, x z = -y,
   * z x = y, z y = -x, y z = x. */
  static const int faces[6][4] = {{2, 0, 1, 0}, {2, 1, 0, 1}, {1, 0, 0, 2},
                                  {1, 1, 2, 0}, {0, 0, 2, 1}, {0, 1, 1, 2}};
  const int n[3] = {d->nx, d->ny, d->nz};
  int f, rc, nt = (int)triangle_count(d->nx, d->ny, d->nz);
  int *ijk = malloc((size_t)nt * 3 * sizeof *ijk), *t = ijk;

  if (!ijk)
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "lattice: cannot allocate %d triangles", nt);
  for (f = 0; f < 6; f++)
    t = face(t, n, faces[f][0], faces[f][1], faces[f][2], faces[f][3]);
  rc = msocl_model_add_triangles(m, nt, ijk);
  free(ijk);
  return rc;
}

int msocl_model_lattice(msocl_model **m, const msocl_lattice_desc *d) {
  int rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!d)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "lattice description is NULL");
  if ((rc = check_desc(d)) || (rc = msocl_model_create(m))) return rc;
  /* validate: the combinations of the model's limits (msocl.h) */
  if ((rc = add_points(*m, d)) || (rc = add_springs(*m, d)) ||
      (rc = add_triangles(*m, d)) || (rc = msocl_model_validate(*m))) {
    msocl_model_destroy(*m);
    *m = NULL;
  }
  return rc;
}
