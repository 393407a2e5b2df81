/* msocl-bench meshcollider: an n x n cloth (1 m a side, hanging from its
 * pinned top edge) alone, against a static 10 000-triangle sphere mesh
 * pressed into it, and against that mesh moving (new vertices every call,
 * so its grid is rebuilt each call): calls of 10 steps (1 kHz updates at
 * dt 1e-4) and calls of a 60 Hz frame's steps, side by side in each
 * repeat, on the default engine (AUTO: GRID); the ratios are the mesh
 * collider's cost a step. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>

/* 2 LON (LAT - 1) = 10 000 triangles; FRAME: 1/60 s at dt 1e-4 */
enum { CALL = 10, FRAME = 167, LAT = 51, LON = 100, RUNS = 4 };

static msocl_model *cloth(int n)
{
  msocl_cloth_desc d;
  const float origin[3] = {-0.5f, 0, 0}, u[3] = {1, 0, 0}, v[3] = {0, -1, 0};
  bench_cloth(&d, n, origin, u, v);
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK)
    return NULL;
  for (int i = 0; i < n; i++)
    if (msocl_model_pin(m, i, 1) != MSOCL_OK) {
      msocl_model_destroy(m);
      return NULL;
    }
  return m;
}

/* A latitude-longitude sphere of radius r about (0, -0.5, z): LAT rings
 * between the poles, LON vertices each; 2 LON (LAT - 1) triangles. */
static int sphere_mesh(float r, float z, float **verts, int **tris)
{
  const int nv = LON * (LAT - 1) + 2, nt = 2 * LON * (LAT - 1);
  float *v = malloc(3 * (size_t)nv * sizeof *v);
  int *t = malloc(3 * (size_t)nt * sizeof *t);
  if (!v || !t) {
    free(v);
    free(t);
    return 0;
  }
  const double pi = 3.14159265358979323846;
  for (int i = 1; i < LAT; i++)
    for (int j = 0; j < LON; j++) {
      const double th = pi * i / LAT, ph = 2 * pi * j / LON;
      float *p = v + 3 * ((i - 1) * LON + j);
      p[0] = (float)(r * sin(th) * cos(ph));
      p[1] = (float)(-0.5 + r * cos(th));
      p[2] = (float)(z + r * sin(th) * sin(ph));
    }
  const int top = nv - 2, bottom = nv - 1;
  v[3 * top] = 0, v[3 * top + 1] = -0.5f + r, v[3 * top + 2] = z;
  v[3 * bottom] = 0, v[3 * bottom + 1] = -0.5f - r, v[3 * bottom + 2] = z;
  int k = 0;
  for (int j = 0; j < LON; j++) {
    const int j1 = (j + 1) % LON;
    t[k++] = top, t[k++] = j1, t[k++] = j;
    const int b = (LAT - 2) * LON;
    t[k++] = bottom, t[k++] = b + j, t[k++] = b + j1;
  }
  for (int i = 0; i + 1 < LAT - 1; i++)
    for (int j = 0; j < LON; j++) {
      const int j1 = (j + 1) % LON, a = i * LON + j, b = i * LON + j1,
                c = (i + 1) * LON + j, d = (i + 1) * LON + j1;
      t[k++] = a, t[k++] = b, t[k++] = c;
      t[k++] = b, t[k++] = d, t[k++] = c;
    }
  *verts = v;
  *tris = t;
  return nv;
}

/* steps in calls of `call`; the moving sim (mover >= 0) gets its mesh
 * shifted along z before each call, at about 1 m/s (*t: its time). */
static int run(msocl_sim *s, int steps, int call, int mover, const float *v0,
               int nv, float *now, float dt, double *t)
{
  for (int done = 0; done < steps; done += call) {
    if (mover >= 0) {
      const float dz = 0.02f * sinf((float)*t * 50.0f);
      *t += call * (double)dt;
      for (int i = 0; i < nv; i++) {
        now[3 * i] = v0[3 * i];
        now[3 * i + 1] = v0[3 * i + 1];
        now[3 * i + 2] = v0[3 * i + 2] + dz;
      }
      const int rc = msocl_sim_set_mesh_collider_vertices(s, 0, now);
      if (rc != MSOCL_OK)
        return rc;
    }
    const int rc = msocl_sim_step(s, call);
    if (rc != MSOCL_OK)
      return rc;
  }
  return MSOCL_OK;
}

int bench_mesh_collider(const struct bench_opts *o, FILE *csv)
{
  msocl_runtime *rt = NULL;
  msocl_device_info info;
  if (bench_open(o, &rt, &info))
    return 1;
  /* none, static, moving in calls of CALL, moving in calls of FRAME */
  static const char *const names[RUNS] = {"none", "static", "moving",
                                          "frame"};
  const int call[RUNS] = {CALL, CALL, CALL, FRAME};
  int steps[RUNS];
  for (int w = 0; w < RUNS; w++)
    steps[w] = (o->steps + call[w] - 1) / call[w] * call[w];
  printf("msocl-bench meshcollider on %s [%s]: %d steps in calls of %d "
         "(frame: %d in calls of %d), best of %d; a %d-triangle sphere "
         "mesh\n", info.name, info.platform_name, steps[0], CALL,
         steps[3], FRAME, o->repeat, 2 * LON * (LAT - 1));
  printf("%5s %-8s %8s %9s %8s\n", "grid", "mesh", "seconds", "steps/s",
         "/none");
  float *v0 = NULL;
  int *t = NULL;
  const int nv = sphere_mesh(0.25f, 0.22f, &v0, &t);
  float *now = nv ? malloc(3 * (size_t)nv * sizeof *now) : NULL;
  int failed = now ? 0 : bench_fail("meshcollider", MSOCL_ERR_NO_MEMORY);
  for (int g = 0; !failed && g < o->ngrids; g++) {
    const int n = o->grids[g];
    msocl_model *m[2] = {cloth(n), cloth(n)};
    int rc = m[0] && m[1] ? MSOCL_OK : MSOCL_ERR_BAD_VALUE;
    if (rc == MSOCL_OK)
      rc = msocl_model_add_mesh_collider(m[1], v0, nv, t,
                                         2 * LON * (LAT - 1), 0.01f, 0.3f);
    msocl_sim_options so;
    msocl_sim_options_init(&so);
    so.dt = 1e-4f;
    so.check_every = 0;
    msocl_sim *s[RUNS] = {NULL};
    for (int w = 0; rc == MSOCL_OK && w < RUNS; w++)
      rc = msocl_sim_create(&s[w], rt, m[w > 0], &so);
    double time[RUNS] = {0};
    for (int w = 0; rc == MSOCL_OK && w < RUNS; w++) /* warm-up */
      rc = run(s[w], call[w], call[w], w >= 2 ? 0 : -1, v0, nv, now, so.dt,
               &time[w]);
    double best[RUNS];
    for (int w = 0; w < RUNS; w++)
      best[w] = INFINITY;
    for (int rep = 0; rc == MSOCL_OK && rep < o->repeat; rep++)
      for (int w = 0; rc == MSOCL_OK && w < RUNS; w++) {
        const double t0 = bench_now();
        rc = run(s[w], steps[w], call[w], w >= 2 ? 0 : -1, v0, nv, now,
                 so.dt, &time[w]);
        const double dt = bench_now() - t0;
        best[w] = dt < best[w] ? dt : best[w];
      }
    if (rc != MSOCL_OK) {
      failed = bench_fail("meshcollider", rc);
    } else {
      for (int w = 0; w < RUNS; w++) {
        struct bench_row r;
        bench_row_init(&r);
        bench_row_device(&r, rt);
        r.layout = names[w];
        r.integrator = bench_integrator_names[0];
        r.math = "precise";
        r.grid = n;
        r.dt = so.dt;
        r.steps = steps[w];
        r.seconds = best[w];
        r.status = "ok";
        bench_row_rates(&r);
        printf("%5d %-8s %8.3f %9.1f %7.2fx\n", n, r.layout, r.seconds,
               r.steps_per_s,
               best[w] / steps[w] / (best[0] / steps[0]));
        bench_csv_row(csv, &r);
      }
      fflush(stdout);
    }
    for (int w = 0; w < RUNS; w++)
      msocl_sim_destroy(s[w]);
    msocl_model_destroy(m[0]);
    msocl_model_destroy(m[1]);
  }
  free(v0);
  free(t);
  free(now);
  msocl_runtime_destroy(rt);
  return failed;
}
