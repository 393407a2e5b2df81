/* Scenes and helpers shared by the device test programs. */
#include "scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TABLE_RADIUS 0.35f
#define K_STRETCH 50.0f
#define K_SHEAR 10.0f
#define K_BEND 10.0f
#define CLOTH_MASS 0.5f

msocl_model *scene_tablecloth(int n)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  d.origin[0] = -0.5f;
  d.origin[1] = 0.05f;
  d.origin[2] = -0.5f;
  /* u = z, v = x: the triangles' normals (u x v) point up. */
  d.u[0] = 0.0f; d.u[1] = 0.0f; d.u[2] = 1.0f;
  d.v[0] = 1.0f; d.v[1] = 0.0f; d.v[2] = 0.0f;
  d.point_mass = CLOTH_MASS / (float)(n * n);
  d.k_stretch = K_STRETCH;
  d.k_shear = K_SHEAR;
  d.k_bend = K_BEND;
  d.damping = 0.0f;
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK)
    return NULL;
  const float top[3] = {0.0f, 0.0f, 0.0f};
  msocl_model_add_table(m, top, TABLE_RADIUS, 0.3f);
  /* viscous rate c/m = 0.5/s: calms the drape without hiding dynamics */
  msocl_model_set_viscous_damping(m, 0.25f / (float)(n * n));
  return m;
}

float scene_tablecloth_dt(int n)
{
  /* Gershgorin: w^2 <= sum_j 4 k_ij / m_i over the 12 springs of an
   * inner point; symplectic Euler is stable for h w < 2. */
  double m = CLOTH_MASS / (double)(n * n);
  double w = sqrt(4.0 * 4.0 * (K_STRETCH + K_SHEAR + K_BEND) / m);
  return (float)(0.5 * 2.0 / w);
}

double scene_table_gap(const float *p)
{
  double rr = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
  double side = rr - TABLE_RADIUS, top = p[1];
  return side > top ? side : top;
}

msocl_model *scene_hanging(int n)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  d.origin[0] = 0.0f; d.origin[1] = 0.0f; d.origin[2] = 0.0f;
  d.u[0] = 1.0f; d.u[1] = 0.0f; d.u[2] = 0.0f;
  d.v[0] = 0.0f; d.v[1] = -1.0f; d.v[2] = 0.0f;
  d.point_mass = CLOTH_MASS / (float)(n * n);
  d.k_stretch = K_STRETCH;
  d.k_shear = K_SHEAR;
  d.k_bend = K_BEND;
  d.damping = 2e-3f;
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK)
    return NULL;
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, n - 1, 1);
  return m;
}

void scene_require_device(const char *program)
{
  msocl_device_info *list = NULL;
  int count = 0;
  int rc = msocl_device_list(&list, &count);
  free(list);
  if (rc != MSOCL_OK || count == 0) {
    printf("%s: SKIP: no OpenCL device: %s\n", program,
           rc != MSOCL_OK ? msocl_last_error() : "no devices");
    exit(77);
  }
}

msocl_runtime *scene_rt;

void scene_setup_cpu(void)
{
  ck_assert_int_eq(msocl_runtime_create(&scene_rt, "cpu"), MSOCL_OK);
}

void scene_teardown(void)
{
  msocl_runtime_destroy(scene_rt);
  scene_rt = NULL;
}

int scene_run(Suite *su)
{
  SRunner *sr = srunner_create(su);
  srunner_set_fork_status(sr, CK_NOFORK);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}

double scene_max_diff(const float *a, const float *b, int n)
{
  double m = 0.0;
  for (int i = 0; i < n; i++) {
    double d = fabs((double)a[i] - (double)b[i]);
    if (!(d <= m))
      m = d; /* NaN propagates as the maximum */
  }
  return m;
}

int scene_cpu_spec(char *spec, size_t cap, int most)
{
  msocl_device_info *list = NULL;
  int count = 0, found = 0;
  spec[0] = '\0';
  if (msocl_device_list(&list, &count) != MSOCL_OK)
    return 0;
  for (int i = 0; i < count && found < most; i++)
    if (list[i].type == MSOCL_DEVICE_CPU) {
      size_t len = strlen(spec);
      snprintf(spec + len, cap - len, "%s%d:%d", found ? "," : "",
               list[i].platform_index, list[i].device_index);
      found++;
    }
  free(list);
  return found;
}

/* Midpoint vertex of edge (i, j), made once: a linear-probing table of
 * edges keyed by their ends. */
struct ico {
  float *v;
  int nv;
  long long *key;
  int *mid;
  int cap;
};

static int ico_mid(struct ico *s, int i, int j)
{
  const long long k = i < j ? (long long)i << 32 | j : (long long)j << 32 | i;
  int h = (int)((unsigned long long)(k * 0x9E3779B97F4A7C15ULL) >> 40) % s->cap;
  while (s->key[h] >= 0 && s->key[h] != k)
    h = (h + 1) % s->cap;
  if (s->key[h] == k)
    return s->mid[h];
  s->key[h] = k;
  float *p = s->v + 3 * s->nv;
  double l = 0;
  for (int c = 0; c < 3; c++) {
    p[c] = 0.5f * (s->v[3 * i + c] + s->v[3 * j + c]);
    l += (double)p[c] * p[c];
  }
  for (int c = 0; c < 3; c++)
    p[c] = (float)(p[c] / sqrt(l));
  return s->mid[h] = s->nv++;
}

int scene_icosphere(int level, double radius, const double centre[3],
                    float **verts, int **tris, int *ntri)
{
  static const int f[20][3] = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const double t = (1.0 + sqrt(5.0)) / 2.0;
  const double b[12][3] = {{-1, t, 0}, {1, t, 0},   {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t},   {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1},   {-t, 0, -1}, {-t, 0, 1}};
  int nt = 20;
  for (int l = 0; l < level; l++)
    nt *= 4;
  const int nv = nt / 2 + 2;
  struct ico s = {malloc(3 * (size_t)nv * sizeof(float)), 12,
                  malloc(3 * (size_t)nt * sizeof(long long)),
                  malloc(3 * (size_t)nt * sizeof(int)), 3 * nt};
  int *tri = malloc(3 * (size_t)nt * sizeof *tri);
  int *next = malloc(3 * (size_t)nt * sizeof *next);
  for (int i = 0; i < 12; i++)
    for (int c = 0; c < 3; c++)
      s.v[3 * i + c] = (float)(b[i][c] / sqrt(1.0 + t * t));
  memcpy(tri, f, sizeof f);
  int cur = 20;
  for (int l = 0; l < level; l++) {
    for (int q = 0; q < s.cap; q++)
      s.key[q] = -1;
    for (int k = 0; k < cur; k++) {
      const int a = tri[3 * k], bb = tri[3 * k + 1], c = tri[3 * k + 2];
      const int ab = ico_mid(&s, a, bb), bc = ico_mid(&s, bb, c),
                ca = ico_mid(&s, c, a);
      const int four[12] = {a, ab, ca, bb, bc, ab, c, ca, bc, ab, bc, ca};
      memcpy(next + 12 * k, four, sizeof four);
    }
    cur *= 4;
    memcpy(tri, next, 3 * (size_t)cur * sizeof *tri);
  }
  for (int i = 0; i < s.nv; i++)
    for (int c = 0; c < 3; c++)
      s.v[3 * i + c] = (float)(centre[c] + radius * s.v[3 * i + c]);
  free(s.key);
  free(s.mid);
  free(next);
  *verts = s.v;
  *tris = tri;
  *ntri = nt;
  return s.nv;
}

msocl_sim *scene_sim(const msocl_model *m, msocl_integrator in, float dt,
                     msocl_layout layout, int check_every)
{
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = dt;
  o.integrator = in;
  if (check_every >= 0)
    o.check_every = check_every;
  o.tuning.layout = layout;
  msocl_sim *s = NULL;
  ck_assert_msg(msocl_sim_create(&s, scene_rt, m, &o) == MSOCL_OK, "%s",
                msocl_last_error());
  return s;
}

msocl_model *scene_curtain(int n, float damping)
{
  const float side = 0.5f;
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  d.origin[0] = -0.5f * side, d.origin[1] = 0.0f, d.origin[2] = 0.0f;
  d.u[0] = side, d.u[1] = 0.0f, d.u[2] = 0.0f;
  d.v[0] = 0.0f, d.v[1] = -side, d.v[2] = 0.0f;
  d.point_mass = 0.2f / (float)(n * n);
  d.k_stretch = 40.0f;
  d.k_shear = 8.0f;
  d.k_bend = 4.0f;
  d.damping = damping;
  msocl_model *m = NULL;
  ck_assert_msg(msocl_model_cloth_grid(&m, &d) == MSOCL_OK, "%s",
                msocl_last_error());
  for (int i = 0; i < n; i++)
    ck_assert_int_eq(msocl_model_pin(m, i, 1), MSOCL_OK);
  return m;
}
