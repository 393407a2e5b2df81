/* What a frame loop pays for the state: the device memory a simulation
 * holds, and the time to step once and read the positions and normals.
 * A cloth of N x N points (GRID under AUTO), symplectic Euler. Public API
 * only, so it links against any build (bench/state_io.sh builds it
 * against two and runs them alternately):
 *
 *   state_io N frames check_every
 *
 * With state_io.sh's shim preloaded it prints the bytes of the OpenCL
 * buffers the second simulation created (the first builds the kernels);
 * without, 0.
 * Results: docs/PERFORMANCE.md ("The state in the planes alone"). */
#define _GNU_SOURCE /* RTLD_DEFAULT, clock_gettime */
#include "msocl.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the shim's count of live buffer bytes (state_io.sh), where loaded */
static size_t cl_bytes(void)
{
  size_t (*f)(void);
  *(void **)&f = dlsym(RTLD_DEFAULT, "clmem_now");
  return f ? f() : 0;
}

static msocl_model *cloth(int n)
{
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  d.point_mass = 0.5f / (float)(n * n);
  d.k_stretch = 50.0f;
  d.k_shear = 10.0f;
  d.k_bend = 10.0f;
  const float origin[3] = {-0.5f, 0.05f, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0};
  memcpy(d.origin, origin, sizeof origin);
  memcpy(d.u, u, sizeof u);
  memcpy(d.v, v, sizeof v);
  msocl_model *m = NULL;
  return msocl_model_cloth_grid(&m, &d) == MSOCL_OK ? m : NULL;
}

int main(int argc, char **argv)
{
  const int n = argc > 1 ? atoi(argv[1]) : 256,
            frames = argc > 2 ? atoi(argv[2]) : 200,
            check = argc > 3 ? atoi(argv[3]) : 100;
  msocl_model *m = cloth(n);
  msocl_runtime *rt = NULL;
  msocl_sim *s = NULL;
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.check_every = check;
  float *xyz = malloc(12 * (size_t)n * n), *nrm = malloc(12 * (size_t)n * n);
  if (!m || !xyz || !nrm || msocl_runtime_create(&rt, NULL) != MSOCL_OK ||
      msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, &o.dt) != MSOCL_OK ||
      msocl_sim_create(&s, rt, m, &o) != MSOCL_OK) {
    fprintf(stderr, "state_io: %s\n", msocl_last_error());
    return 1;
  }
  msocl_sim_destroy(s);
  const size_t b0 = cl_bytes();
  if (msocl_sim_create(&s, rt, m, &o) != MSOCL_OK)
    return 1;
  const size_t b1 = cl_bytes();
  msocl_sim_step(s, 1);
  msocl_sim_read_positions(s, xyz);
  msocl_sim_read_normals(s, nrm);
  double ts = 0, tr = 0, tn = 0;
  for (int f = 0; f < frames; f++) {
    const double t0 = now();
    msocl_sim_step(s, 1);
    const double t1 = now();
    msocl_sim_read_positions(s, xyz);
    const double t2 = now();
    msocl_sim_read_normals(s, nrm);
    const double t3 = now();
    ts += t1 - t0;
    tr += t2 - t1;
    tn += t3 - t2;
  }
  const size_t mid = 3 * ((size_t)n * n / 2) + 1;
  printf("%dx%d check_every %d: buffers %.1f MiB, %.1f B a point; us a "
         "frame: step %.1f, read_positions %.1f, read_normals %.1f "
         "(y %.9g, normal y %.9g)\n",
         n, n, check, (double)(b1 - b0) / 1048576.0,
         (double)(b1 - b0) / ((double)n * n), 1e6 * ts / frames,
         1e6 * tr / frames, 1e6 * tn / frames, xyz[mid], nrm[mid]);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
  free(xyz);
  free(nrm);
  return 0;
}
