/* Triangle-mesh models from Wavefront OBJ: a point per vertex, springs
 * along the edges (and across them to bend), masses from surface area. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "mesh_edges.h"
#include "obj_parse.h"

/* A triangle whose height is below this fraction of its longest edge has
 * collinear corners as far as float coordinates can tell. */
#define FLAT 1e-6

void msocl_obj_desc_init(msocl_obj_desc *d) {
  if (!d) return;
  d->density = 0.1f;
  d->k_edge = 100.0f;
  d->k_bend = 0.0f;
  d->damping = 0.0f;
}

static int check_desc(const msocl_obj_desc *d) {
  if (!d) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "OBJ description is NULL");
  if (!isfinite(d->density) || !isfinite(d->k_edge) || !isfinite(d->k_bend) ||
      !isfinite(d->damping))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "OBJ: density %g, k_edge %g, k_bend %g, damping %g: "
                       "not all finite",
                       d->density, d->k_edge, d->k_bend, d->damping);
  if (!(d->density > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS, "OBJ: density %g must be > 0",
                       d->density);
  if (!(d->k_edge > 0))
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "OBJ: k_edge %g must be > 0",
                       d->k_edge);
  if (d->k_bend < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "OBJ: k_bend %g must be >= 0",
                       d->k_bend);
  if (d->damping < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "OBJ: damping %g must be >= 0",
                       d->damping);
  return MSOCL_OK;
}

/* The area of every triangle, in double; refuses flat triangles, and edges
 * too long for a float rest length. */
static int areas(const struct msocl__obj *o, double *area) {
  int t, c, i;

  for (t = 0; t < o->nt; t++) {
    const int *k = o->tri + 3 * (size_t)t;
    double e[3][3], l2, lmax2 = 0, n[3];

    for (c = 0; c < 3; c++) {
      const float *p = o->xyz + 3 * (size_t)k[c];
      const float *q = o->xyz + 3 * (size_t)k[(c + 1) % 3];
      for (i = 0, l2 = 0; i < 3; i++) {
        e[c][i] = (double)q[i] - p[i];
        l2 += e[c][i] * e[c][i];
      }
      if (l2 > lmax2) lmax2 = l2;
    }
    if (sqrt(lmax2) > FLT_MAX)
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "OBJ line %d: an edge of the face is %g long, more "
                         "than a float holds",
                         o->tline[t], sqrt(lmax2));
    n[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    n[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    n[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    area[t] = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (2 * area[t] <= FLAT * lmax2)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "OBJ line %d: triangle of vertices %d, %d, %d has no "
                         "area (its corners are collinear)",
                         o->tline[t], k[0] + 1, k[1] + 1, k[2] + 1);
  }
  return MSOCL_OK;
}

/* density x a third of the area of each triangle at the vertex. A vertex
 * on no triangle (common: left over from editing) gets the mass of an
 * average vertex, so it is a valid point, and no springs. */
static int masses(const struct msocl__obj *o, const double *area,
                  double density, float *mass) {
  double *share = calloc((size_t)o->nv, sizeof *share), total = 0, mean;
  int t, c, i, rc = MSOCL_OK;

  if (!share)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "OBJ: cannot allocate %d masses",
                       o->nv);
  for (t = 0; t < o->nt; t++) {
    total += area[t];
    for (c = 0; c < 3; c++) share[o->tri[3 * (size_t)t + c]] += area[t] / 3;
  }
  mean = total / o->nt / 3;
  for (i = 0; i < o->nv && !rc; i++) {
    double x = density * (share[i] > 0 ? share[i] : mean);
    if (!(x <= FLT_MAX))
      rc = msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "OBJ line %d: vertex %d gets a mass of %g kg, more "
                       "than a float holds",
                       o->vline[i], i + 1, x);
    else if (!((mass[i] = (float)x) > 0))
      rc = msocl__fail(MSOCL_ERR_BAD_MASS,
                       "OBJ line %d: vertex %d gets a mass of %g kg, too "
                       "small for a float",
                       o->vline[i], i + 1, x);
  }
  free(share);
  return rc;
}

/* Edge springs, then bending springs; each rests at its length in the
 * file. */
static int add_springs(msocl_model *m, const struct msocl__obj *o,
                       const msocl_obj_desc *d) {
  int *ij, ne, nb, i, rc;
  float *k, *damp = NULL;

  if ((rc = msocl__mesh_springs(o->nt, o->tri, d->k_bend > 0, &ij, &ne, &nb)))
    return rc;
  k = malloc((size_t)(ne + nb) * sizeof *k);
  if (d->damping > 0) damp = malloc((size_t)(ne + nb) * sizeof *damp);
  if (!k || (d->damping > 0 && !damp)) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "OBJ: cannot allocate %d springs",
                     ne + nb);
  } else {
    for (i = 0; i < ne + nb; i++) {
      k[i] = i < ne ? d->k_edge : d->k_bend;
      if (damp) damp[i] = d->damping;
    }
    rc = msocl_model_add_springs(m, ne + nb, ij, k, NULL, damp);
  }
  free(ij);
  free(k);
  free(damp);
  return rc;
}

/* The sizes below cannot wrap: the parser already holds 3 ints a triangle
 * and 3 floats a vertex. */
static int build(msocl_model **m, const struct msocl__obj *o,
                 const msocl_obj_desc *d) {
  double *area = malloc((size_t)o->nt * sizeof *area);
  float *mass = malloc((size_t)o->nv * sizeof *mass);
  int rc;

  if (!area || !mass)
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY,
                     "OBJ: cannot allocate %d points and %d triangles", o->nv,
                     o->nt);
  else if (!(rc = areas(o, area)) && !(rc = masses(o, area, d->density, mass)) &&
           !(rc = msocl_model_create(m)) &&
           ((rc = msocl_model_add_points(*m, o->nv, o->xyz, mass, NULL)) ||
            (rc = add_springs(*m, o, d)) ||
            (rc = msocl_model_add_triangles(*m, o->nt, o->tri)) ||
            (rc = msocl_model_validate(*m)))) {
    msocl_model_destroy(*m);
    *m = NULL;
  }
  free(area);
  free(mass);
  return rc;
}

int msocl_model_from_obj_text(msocl_model **m, const char *text, size_t len,
                              const msocl_obj_desc *d) {
  struct msocl__obj o;
  int rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!text) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "OBJ text is NULL");
  if ((rc = check_desc(d)) || (rc = msocl__obj_parse(&o, text, len)))
    return rc;
  rc = build(m, &o, d);
  msocl__obj_free(&o);
  return rc;
}

int msocl_model_from_obj(msocl_model **m, const char *path,
                         const msocl_obj_desc *d) {
  char *text = NULL;
  size_t len = 0;
  int rc;

  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  *m = NULL;
  if (!path) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "OBJ path is NULL");
  if ((rc = check_desc(d)) ||
      (rc = msocl__obj_read_file(path, MSOCL_OBJ_MAX_FILE_BYTES, &text, &len)))
    return rc;
  /* The message then starts with the file's name, as a compiler's does. */
  if ((rc = msocl_model_from_obj_text(m, text, len, d)))
    rc = msocl__fail(rc, "%s: %s", path, msocl_last_error());
  free(text);
  return rc;
}
