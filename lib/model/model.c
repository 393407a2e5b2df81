/* The host-side model: points, springs, triangles and force parameters,
 * checked on the way in so that every later stage may trust them. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* ------------------------------------------------------------ capacity */

/* The most items an array may hold: an item's first index (3i for a point,
 * 2s for a spring) must fit an int, here, in the adjacency and on the
 * device, and the array's bytes must fit a size_t. */
static int max_items(int per, size_t bytes_per) {
  size_t by_size = SIZE_MAX / bytes_per;
  int by_int = INT_MAX / per;
  return by_size < (size_t)by_int ? (int)by_size : by_int;
}

#define MAX_POINTS max_items(3, 3 * sizeof(float))
#define MAX_SPRINGS max_items(2, 2 * sizeof(int))
#define MAX_TRIANGLES max_items(3, 3 * sizeof(int))

static int too_many(const char *what, int have, int n, int max) {
  return msocl__fail(MSOCL_ERR_TOO_MANY,
                     "adding %d %s to %d exceeds the limit of %d", n, what,
                     have, max);
}

/* Doubling keeps n appends at O(n) copies in all. */
static int new_capacity(int cap, int need, int max) {
  long long c = cap > 0 ? cap : 16;
  while (c < need) c *= 2;
  return c > max ? max : (int)c;
}

static int no_memory(const char *what, int cap) {
  return msocl__fail(MSOCL_ERR_NO_MEMORY, "cannot grow the %s to %d", what,
                     cap);
}

/* Each array that moved is stored at once, so a later failure leaves every
 * pointer valid; only the capacity waits until all have grown. */
static int reserve_points(msocl_model *m, int need) {
  int cap;
  float *f;
  unsigned char *u;

  if (need <= m->cap) return MSOCL_OK;
  cap = new_capacity(m->cap, need, MAX_POINTS);
  if (!(f = realloc(m->pos, (size_t)cap * 3 * sizeof *f)))
    return no_memory("points", cap);
  m->pos = f;
  if (!(f = realloc(m->mass, (size_t)cap * sizeof *f)))
    return no_memory("points", cap);
  m->mass = f;
  if (!(u = realloc(m->pinned, (size_t)cap))) return no_memory("points", cap);
  m->pinned = u;
  m->cap = cap;
  return MSOCL_OK;
}

/* m->damp stays NULL until a spring with damping arrives, so a model
 * without dashpots carries none (and its kernels need not read them). */
static int reserve_springs(msocl_model *m, int need, int want_damp) {
  int cap;
  int *ij;
  float *f;

  if (need > m->scap) {
    cap = new_capacity(m->scap, need, MAX_SPRINGS);
    if (!(ij = realloc(m->ij, (size_t)cap * 2 * sizeof *ij)))
      return no_memory("springs", cap);
    m->ij = ij;
    if (!(f = realloc(m->k, (size_t)cap * sizeof *f)))
      return no_memory("springs", cap);
    m->k = f;
    if (!(f = realloc(m->rest, (size_t)cap * sizeof *f)))
      return no_memory("springs", cap);
    m->rest = f;
    if (m->damp) {
      if (!(f = realloc(m->damp, (size_t)cap * sizeof *f)))
        return no_memory("springs", cap);
      m->damp = f;
    }
    m->scap = cap;
  }
  if (want_damp && !m->damp) {
    if (!(m->damp = calloc((size_t)m->scap, sizeof *m->damp)))
      return no_memory("spring damping", m->scap);
  }
  return MSOCL_OK;
}

static int reserve_triangles(msocl_model *m, int need) {
  int cap;
  int *t;

  if (need <= m->tcap) return MSOCL_OK;
  cap = new_capacity(m->tcap, need, MAX_TRIANGLES);
  if (!(t = realloc(m->tri, (size_t)cap * 3 * sizeof *t)))
    return no_memory("triangles", cap);
  m->tri = t;
  m->tcap = cap;
  return MSOCL_OK;
}

/* -------------------------------------------------------------- checks */

/* The limits of msocl.h (at msocl_model_add_points and _add_springs) that
 * keep a step's float arithmetic finite: coordinates and forces as
 * internal.h says, and a mass in [FLT_MIN, 1/FLT_MIN], whose 1/m is a
 * normal float. */
#define COORD_MAX MSOCL__COORD_MAX
#define MASS_MIN ((double)FLT_MIN)
#define MASS_MAX (1.0 / (double)FLT_MIN)
#define FORCE_MAX MSOCL__FORCE_MAX

/* Indices in messages count from the start of the caller's arrays. */
static int check_point(int i, const float *p, float mass) {
  int c;
  for (c = 0; c < 3; c++) {
    if (!isfinite(p[c]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "point %d: %c = %g is not finite", i, "xyz"[c], p[c]);
    if (fabs(p[c]) > COORD_MAX)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "point %d: |%c| = %g exceeds %g, past which squared "
                         "distances overflow a float",
                         i, "xyz"[c], fabs(p[c]), COORD_MAX);
  }
  if (!isfinite(mass))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "point %d: mass %g is not finite",
                       i, mass);
  if (!(mass > 0))
    return msocl__fail(MSOCL_ERR_BAD_MASS, "point %d: mass %g must be > 0", i,
                       mass);
  if (mass < MASS_MIN || mass > MASS_MAX)
    return msocl__fail(MSOCL_ERR_BAD_MASS,
                       "point %d: mass %g is outside [FLT_MIN, 1/FLT_MIN] = "
                       "[%g, %g], where 1/m is a normal float",
                       i, mass, MASS_MIN, MASS_MAX);
  return MSOCL_OK;
}

static int check_index(const char *what, int item, int index, int n) {
  if (index < 0 || index >= n)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "%s %d: point index %d out of range [0, %d)", what, item,
                       index, n);
  return MSOCL_OK;
}

static int check_spring_ends(int s, int i, int j, int n) {
  int rc;
  if ((rc = check_index("spring", s, i, n)) ||
      (rc = check_index("spring", s, j, n)))
    return rc;
  if (i == j)
    return msocl__fail(MSOCL_ERR_SELF_SPRING,
                       "spring %d: connects point %d to itself", s, i);
  return MSOCL_OK;
}

/* A coefficient that must be finite and >= 0. */
static int check_coef(int s, const char *what, float x) {
  if (!isfinite(x))
    return msocl__fail(MSOCL_ERR_NOT_FINITE, "spring %d: %s %g is not finite",
                       s, what, x);
  if (x < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "spring %d: %s %g must be >= 0", s,
                       what, x);
  return MSOCL_OK;
}

/* Stiffness or dashpot x times a length: the spring's force at that
 * stretch (or closing speed a second) must stay within FORCE_MAX; `len`
 * at least 1 m, so that a short or unstretched spring is held to it too. */
static int check_force(int s, const char *what, float x, double len) {
  double f = (double)x * (len > 1.0 ? len : 1.0);
  if (f > FORCE_MAX)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "spring %d: %s %g x %s %g = %g exceeds the force limit "
                       "%g",
                       s, what, x, what[0] == 's' ? "length" : "speed",
                       len > 1.0 ? len : 1.0, f, FORCE_MAX);
  return MSOCL_OK;
}

static int check_spring_forces(int s, float k, const float *c, double len) {
  int rc = check_force(s, "stiffness", k, len);
  if (rc == MSOCL_OK && c) rc = check_force(s, "damping", *c, len);
  return rc;
}

/* In double, so a rest length is as exact as a float can hold. */
static double distance(const msocl_model *m, int i, int j) {
  double d2 = 0;
  int c;
  for (c = 0; c < 3; c++) {
    double d = (double)m->pos[3 * i + c] - m->pos[3 * j + c];
    d2 += d * d;
  }
  return sqrt(d2);
}

/* The rest length a spring will get; NOT_FINITE if the ends lie so far
 * apart that their distance overflows a float. */
static int rest_length(const msocl_model *m, int s, int i, int j,
                       const float *rest, float *out) {
  if (rest && !isfinite(rest[s]))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "spring %d: rest length %g is not finite", s, rest[s]);
  *out = rest && rest[s] >= 0 ? rest[s] : (float)distance(m, i, j);
  if (!isfinite(*out))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "spring %d: distance %g between points %d and %d "
                       "overflows a float",
                       s, distance(m, i, j), i, j);
  return MSOCL_OK;
}

static int check_triangle(int t, const int *ijk, int n) {
  int c, rc;
  for (c = 0; c < 3; c++)
    if ((rc = check_index("triangle", t, ijk[c], n))) return rc;
  if (ijk[0] == ijk[1] || ijk[1] == ijk[2] || ijk[0] == ijk[2])
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "triangle %d: corners (%d, %d, %d) are not distinct", t,
                       ijk[0], ijk[1], ijk[2]);
  return MSOCL_OK;
}

static int check_gravity(const float g[3]) {
  if (!isfinite(g[0]) || !isfinite(g[1]) || !isfinite(g[2]))
    return msocl__fail(MSOCL_ERR_NOT_FINITE,
                       "gravity (%g, %g, %g) is not finite", g[0], g[1], g[2]);
  return MSOCL_OK;
}

static int check_viscous(float c) { return msocl__check_damping(0, c); }

/* Shared guard of the adding calls: handle, arrays, count, room. */
static int check_add(const msocl_model *m, const void *a, const void *b, int n,
                     const char *what, int have, int max) {
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if (!a || !b)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s: required array is NULL",
                       what);
  if (n <= 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%s: count %d must be > 0", what,
                       n);
  if (n > max - have) return too_many(what, have, n, max);
  return MSOCL_OK;
}

/* ------------------------------------------------------ create/destroy */

int msocl_model_create(msocl_model **m) {
  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model out-pointer is NULL");
  if (!(*m = calloc(1, sizeof **m)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "cannot allocate a model");
  (*m)->gravity[1] = -9.81f;
  (*m)->air = 1.0f;
  return MSOCL_OK;
}

void msocl_model_destroy(msocl_model *m) {
  if (!m) return;
  msocl__live_drop(m);
  free(m->pos);
  free(m->mass);
  free(m->pinned);
  free(m->ij);
  free(m->k);
  free(m->rest);
  free(m->damp);
  free(m->tri);
  msocl__mesh_colliders_free(m);
  free(m);
}

/* ---------------------------------------------------------------- adds */

/* Every add checks all its input before it touches the model, so a failed
 * call leaves the model exactly as it was. */
int msocl_model_add_points(msocl_model *m, int n, const float *xyz,
                           const float *mass, int *first) {
  int i, rc;

  msocl__clear_error();
  if ((rc = check_add(m, xyz, mass, n, "points", m ? m->n : 0, MAX_POINTS)))
    return rc;
  for (i = 0; i < n; i++)
    if ((rc = check_point(i, xyz + 3 * i, mass[i]))) return rc;
  if ((rc = reserve_points(m, m->n + n))) return rc;
  memcpy(m->pos + 3 * m->n, xyz, (size_t)n * 3 * sizeof *xyz);
  memcpy(m->mass + m->n, mass, (size_t)n * sizeof *mass);
  memset(m->pinned + m->n, 0, (size_t)n);
  if (first) *first = m->n;
  m->n += n;
  return MSOCL_OK;
}

int msocl_model_add_springs(msocl_model *m, int n, const int *ij,
                            const float *stiffness, const float *rest,
                            const float *damping) {
  int s, rc, want_damp = 0;
  float r;

  msocl__clear_error();
  if ((rc = check_add(m, ij, stiffness, n, "springs", m ? m->ns : 0,
                      MAX_SPRINGS)))
    return rc;
  for (s = 0; s < n; s++) {
    if ((rc = check_spring_ends(s, ij[2 * s], ij[2 * s + 1], m->n)) ||
        (rc = check_coef(s, "stiffness", stiffness[s])) ||
        (damping && (rc = check_coef(s, "damping", damping[s]))) ||
        (rc = rest_length(m, s, ij[2 * s], ij[2 * s + 1], rest, &r)) ||
        (rc = check_spring_forces(
             s, stiffness[s], damping ? &damping[s] : NULL,
             fmax(r, distance(m, ij[2 * s], ij[2 * s + 1])))))
      return rc;
    if (damping && damping[s] > 0) want_damp = 1;
  }
  if ((rc = reserve_springs(m, m->ns + n, want_damp))) return rc;
  /* Appended in the caller's order: it fixes the order of summation. */
  for (s = 0; s < n; s++) {
    int t = m->ns + s;
    m->ij[2 * t] = ij[2 * s];
    m->ij[2 * t + 1] = ij[2 * s + 1];
    m->k[t] = stiffness[s];
    (void)rest_length(m, s, ij[2 * s], ij[2 * s + 1], rest, &m->rest[t]);
    if (m->damp) m->damp[t] = damping ? damping[s] : 0.0f;
  }
  m->ns += n;
  return MSOCL_OK;
}

int msocl_model_add_triangles(msocl_model *m, int n, const int *ijk) {
  int t, rc;

  msocl__clear_error();
  if ((rc = check_add(m, ijk, ijk, n, "triangles", m ? m->nt : 0,
                      MAX_TRIANGLES)))
    return rc;
  for (t = 0; t < n; t++)
    if ((rc = check_triangle(t, ijk + 3 * t, m->n))) return rc;
  if ((rc = reserve_triangles(m, m->nt + n))) return rc;
  memcpy(m->tri + 3 * m->nt, ijk, (size_t)n * 3 * sizeof *ijk);
  m->nt += n;
  return MSOCL_OK;
}

/* ---------------------------------------------------------- parameters */

int msocl_model_pin(msocl_model *m, int point, int pinned) {
  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if (point < 0 || point >= m->n)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "pin: point index %d out of range [0, %d)", point, m->n);
  int rc = msocl__live_refuse(m, "msocl_model_pin", "msocl_sim_pin");
  if (rc) return rc;
  m->pinned[point] = pinned != 0;
  return MSOCL_OK;
}

int msocl_model_set_gravity(msocl_model *m, float gx, float gy, float gz) {
  float g[3];
  int rc;

  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  g[0] = gx;
  g[1] = gy;
  g[2] = gz;
  if ((rc = check_gravity(g))) return rc;
  if ((rc = msocl__live_refuse(m, "msocl_model_set_gravity",
                               "msocl_sim_set_gravity")))
    return rc;
  memcpy(m->gravity, g, sizeof g);
  return MSOCL_OK;
}

static int check_air(float f) { return msocl__check_damping(1, f); }

int msocl_model_set_air_resistance(msocl_model *m, float factor) {
  int rc;

  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if ((rc = check_air(factor))) return rc;
  if ((rc = msocl__live_refuse(m, "msocl_model_set_air_resistance",
                               "msocl_sim_set_air_resistance")))
    return rc;
  m->air = factor;
  return MSOCL_OK;
}

int msocl_model_set_viscous_damping(msocl_model *m, float c) {
  int rc;

  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if ((rc = check_viscous(c))) return rc;
  if ((rc = msocl__live_refuse(m, "msocl_model_set_viscous_damping",
                               "msocl_sim_set_viscous_damping")))
    return rc;
  m->viscous = c;
  return MSOCL_OK;
}

/* ------------------------------------------------------------- queries */

static int null_args(const void *m, const void *out) {
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if (!out) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "output pointer is NULL");
  return MSOCL_OK;
}

int msocl_model_point_count(const msocl_model *m, int *n) {
  int rc;
  msocl__clear_error();
  if ((rc = null_args(m, n))) return rc;
  *n = m->n;
  return MSOCL_OK;
}

int msocl_model_spring_count(const msocl_model *m, int *n) {
  int rc;
  msocl__clear_error();
  if ((rc = null_args(m, n))) return rc;
  *n = m->ns;
  return MSOCL_OK;
}

int msocl_model_max_degree(const msocl_model *m, int *degree) {
  int *deg, i, s, rc, max = 0;

  msocl__clear_error();
  if ((rc = null_args(m, degree))) return rc;
  if (m->n > 0) {
    if (!(deg = calloc((size_t)m->n, sizeof *deg)))
      return msocl__fail(MSOCL_ERR_NO_MEMORY,
                         "cannot count the degrees of %d points", m->n);
    for (s = 0; s < 2 * m->ns; s++) deg[m->ij[s]]++;
    for (i = 0; i < m->n; i++)
      if (deg[i] > max) max = deg[i];
    free(deg);
  }
  *degree = max;
  return MSOCL_OK;
}

int msocl_model_get_positions(const msocl_model *m, float *xyz) {
  int rc;
  msocl__clear_error();
  if ((rc = null_args(m, xyz))) return rc;
  if (m->n > 0) memcpy(xyz, m->pos, (size_t)m->n * 3 * sizeof *xyz);
  return MSOCL_OK;
}

int msocl_model_triangles(const msocl_model *m, int *n, const int **ijk) {
  int rc;
  msocl__clear_error();
  if ((rc = null_args(m, n)) || (rc = null_args(m, ijk))) return rc;
  *n = m->nt;
  *ijk = m->tri;
  return MSOCL_OK;
}

/* The diagonal of the points' bounding box, in double. */
static double extent(const msocl_model *m) {
  double lo[3], hi[3], d2 = 0;
  int i, c;
  for (c = 0; c < 3; c++) lo[c] = hi[c] = m->pos[c];
  for (i = 1; i < m->n; i++)
    for (c = 0; c < 3; c++) {
      lo[c] = fmin(lo[c], m->pos[3 * i + c]);
      hi[c] = fmax(hi[c], m->pos[3 * i + c]);
    }
  for (c = 0; c < 3; c++) d2 += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  return sqrt(d2);
}

/* The combinations no single add can see, with every spring stretched
 * by (and every dashpot closing at, a second) the larger of its rest
 * length and the model's extent: each spring's force, and each free
 * point's acceleration from its springs, its viscous damping and its
 * weight, within FORCE_MAX. */
static int check_combined(const msocl_model *m) {
  const double ext = extent(m), ext1 = ext > 1.0 ? ext : 1.0;
  const double g = sqrt((double)m->gravity[0] * m->gravity[0] +
                        (double)m->gravity[1] * m->gravity[1] +
                        (double)m->gravity[2] * m->gravity[2]);
  double *pull;
  int i, s, rc = MSOCL_OK;

  if ((double)m->viscous * ext1 > FORCE_MAX)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "viscous damping %g x speed %g (the model's extent a "
                       "second) exceeds the force limit %g",
                       m->viscous, ext1, FORCE_MAX);
  if (!(pull = calloc((size_t)m->n, sizeof *pull)))
    return msocl__fail(MSOCL_ERR_NO_MEMORY,
                       "cannot check the forces on %d points", m->n);
  for (s = 0; rc == MSOCL_OK && s < m->ns; s++) {
    const double len = fmax(m->rest[s], ext);
    const float c = m->damp ? m->damp[s] : 0.0f;
    rc = check_spring_forces(s, m->k[s], m->damp ? &c : NULL, len);
    pull[m->ij[2 * s]] += ((double)m->k[s] + c) * fmax(len, 1.0);
    pull[m->ij[2 * s + 1]] += ((double)m->k[s] + c) * fmax(len, 1.0);
  }
  for (i = 0; rc == MSOCL_OK && i < m->n; i++) {
    const double a = (pull[i] + (double)m->viscous * ext1) / m->mass[i];
    if (m->pinned[i]) continue; /* never moves: its 1/m is never used */
    if (a > FORCE_MAX)
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "point %d: its springs and damping at the model's "
                       "extent %g give its mass %g an acceleration of %g, "
                       "past the limit %g",
                       i, ext, m->mass[i], a, FORCE_MAX);
    else if (m->mass[i] * g > FORCE_MAX)
      rc = msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "point %d: weight %g x %g = %g exceeds the force limit "
                       "%g",
                       i, m->mass[i], g, m->mass[i] * g, FORCE_MAX);
  }
  free(pull);
  return rc;
}

/* Re-runs the checks of the adding calls over the whole model, so a model
 * that reaches a device is known good whatever path built it, then checks
 * the combinations. */
int msocl_model_validate(const msocl_model *m) {
  int i, rc;

  msocl__clear_error();
  if (!m) return msocl__fail(MSOCL_ERR_NULL_HANDLE, "model is NULL");
  if (m->n == 0) return msocl__fail(MSOCL_ERR_EMPTY, "model has no points");
  for (i = 0; i < m->n; i++)
    if ((rc = check_point(i, m->pos + 3 * i, m->mass[i]))) return rc;
  for (i = 0; i < m->ns; i++)
    if ((rc = check_spring_ends(i, m->ij[2 * i], m->ij[2 * i + 1], m->n)) ||
        (rc = check_coef(i, "stiffness", m->k[i])) ||
        (rc = check_coef(i, "rest length", m->rest[i])) ||
        (m->damp && (rc = check_coef(i, "damping", m->damp[i]))))
      return rc;
  for (i = 0; i < m->nt; i++)
    if ((rc = check_triangle(i, m->tri + 3 * i, m->n))) return rc;
  if ((rc = check_gravity(m->gravity)) || (rc = check_viscous(m->viscous)) ||
      (rc = check_air(m->air)))
    return rc;
  for (i = 0; i < m->ncol; i++) {
    const struct msocl__collider *c = &m->col[i];
    if (!isfinite(c->p[0]) || !isfinite(c->p[1]) || !isfinite(c->p[2]) ||
        !isfinite(c->p[3]) || !isfinite(c->friction))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "collider %d: parameter is not finite", i);
  }
  return check_combined(m);
}

int msocl__grid_intact(const msocl_model *m)
{
  const long long layers = m->grid.nz > 0 ? m->grid.nz : 1;
  return m->grid.nx >= 2 && m->grid.ns == m->ns &&
         (long long)m->grid.nx * m->grid.ny * layers == m->n;
}
