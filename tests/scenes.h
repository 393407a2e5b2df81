/* Scenes and helpers shared by the device test programs. */
#ifndef MSOCL_TEST_SCENES_H
#define MSOCL_TEST_SCENES_H

#include "msocl.h"

/* The paper's scene: an n x n square tablecloth, 1 m a side, falling from
 * 5 cm onto a round table of radius 0.35 m whose top is at y = 0. */
msocl_model *scene_tablecloth(int n);
/* Stable dt for scene_tablecloth(n) (half the symplectic Euler limit of its
 * Gershgorin frequency bound). */
float scene_tablecloth_dt(int n);
/* An n x n cloth, 1 m a side, hanging in the x-y plane from its two top
 * corners, with dashpots; no contact. */
msocl_model *scene_hanging(int n);
/* An n x n cloth, 0.5 m a side, 0.2 kg, hanging in the x-y plane (z 0,
 * centred on x 0) from its whole top row, with dashpots `damping` (0:
 * GRID's symplectic Euler runs kernels/planes_rows.cl on a CPU, for n a
 * multiple of 16): the moving colliders' curtain. */
msocl_model *scene_curtain(int n, float damping);
/* Signed distance-like value of the tablecloth's table (>= 0 outside). */
double scene_table_gap(const float *p);

/* Exits 77 (automake SKIP), saying why, when no OpenCL device exists;
 * otherwise returns. Call in main() before srunner_run_all. */
void scene_require_device(const char *program);

/* Writes into spec a device spec naming up to `most` CPU devices (PoCL's
 * pthread devices: one spec word each); returns how many. */
#include <stddef.h>
int scene_cpu_spec(char *spec, size_t cap, int most);

/* A runtime on the first CPU device, for checked fixtures. */
extern msocl_runtime *scene_rt;
void scene_setup_cpu(void);
void scene_teardown(void);

/* Runs a suite without forking (PoCL hangs in fork()ed children once the
 * parent has used OpenCL); returns the exit status. */
#include <check.h>
int scene_run(Suite *su);

/* An icosphere: the icosahedron subdivided `level` times, its vertices
 * on the sphere of `radius` about centre, triangles wound outward (seen
 * from outside, counter-clockwise). Returns the vertex count; *verts (3
 * floats a vertex) and *tris (3 ints a triangle, *ntri of them) are
 * malloc'd. */
int scene_icosphere(int level, double radius, const double centre[3],
                    float **verts, int **tris, int *ntri);

/* A simulation of m on scene_rt (scene_setup_cpu's runtime): integrator
 * in, step dt, layout; check_every >= 0 sets the
 * blow-up check's period (0: off), < 0 keeps its default. Fails the test,
 * with the library's message, if it cannot be made. */
msocl_sim *scene_sim(const msocl_model *m, msocl_integrator in, float dt,
                     msocl_layout layout, int check_every);

/* max |a - b| over n floats. */
double scene_max_diff(const float *a, const float *b, int n);

#endif
