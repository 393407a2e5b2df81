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
