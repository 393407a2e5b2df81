/* The paper's scene: a square tablecloth falls onto a round table. Prints
 * steps per second and writes the final mesh as OBJ or PLY.
 *
 *   msocl-tablecloth [-n GRID] [-s STEPS] [-d DEVICE_SPEC] [-l LAYOUT]
 *                    [-m MATH] [-i INTEGRATOR] [-S STRAIN [-I SWEEPS]]
 *                    [-p PARTS [-c STEPS] [-O]] [-f] [-C|-V] [-k STEPS]
 *                    [-o OUT.obj|OUT.ply]   (-h: all of them)
 */
#include "cli.h"

#include <msocl.h>

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PROG "msocl-tablecloth"
#define OPTIONS ":n:s:d:l:m:o:i:S:I:p:c:k:fOCVh"

static const char *const maths[] = {"precise", "relaxed"};
static const char *const strains[] = {"none", "provot", "velocity"};

static int usage(void)
{
  return cli_help(
      "usage: " PROG " [-n GRID] [-s STEPS] [-d DEVICE_SPEC]\n"
      "  [-l auto|image2d|buffer|edges|grid] [-m precise|relaxed]\n"
      "  [-i symplectic|explicit|verlet|rk4|implicit]\n"
      "  [-S none|provot|velocity [-I SWEEPS]] [-p PARTS [-c STEPS] [-O]]\n"
      "  [-f] [-C|-V] [-k STEPS] [-o OUT.obj|OUT.ply]\n"
      "The paper's tablecloth falling onto a round table; prints steps/s.\n"
      "  -n  points along each side of the cloth, 2 to 13378 (default 64)\n"
      "  -s  steps to time, >= 0 (default 2000)\n"
      "  -d  OpenCL device spec, as MSOCL_DEVICE (default: that variable)\n"
      "  -l  spring layout (default auto: the library's choice)\n"
      "  -m  math mode (default precise)\n"
      "  -i  integrator (default symplectic; explicit runs at its own,\n"
      "      far smaller, stable step)\n"
      "  -S  strain limiting (default none)\n"
      "  -I  strain limiting's sweeps a step, 1 to 1000 (default 10)\n"
      "  -p  split the cloth over PARTS of the chosen devices, -1 (all) to\n"
      "      16 (default 1)\n"
      "  -c  weigh the devices by a calibration run of STEPS steps\n"
      "      (default 0: equal shares)\n"
      "  -O  split, all kernels then all copies (default: the points\n"
      "      other devices read first, their copies beside the rest)\n"
      "  -f  both passes of a step in one kernel (same result)\n"
      "  -C, -V: BUFFER with a spring-class byte in every slot, or with\n"
      "      rest length and stiffness in every slot (default: the\n"
      "      library's choice; same result)\n"
      "  -k  steps a msocl_sim_step call, as a frame loop (default 0: all\n"
      "      in one call; on a terminal, calls of about a quarter second\n"
      "      for the progress line)\n"
      "  -o  final mesh, OBJ or PLY by extension (default tablecloth.obj)\n"
      "  -h, --help  this text\n");
}

/* The tablecloth: 1 m square, 0.5 kg, 5 cm above a table of radius 0.35 m;
 * spring stiffness per type as in the paper's three spring kinds. */
static msocl_model *build(int n, int integrator, float *dt)
{
  const float mass = 0.5f, ks = 50.0f, kh = 10.0f, kb = 10.0f;
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  d.nx = d.ny = n;
  /* u = z, v = x, so the triangles' normals (u x v) point up. */
  const float origin[3] = {-0.5f, 0.05f, -0.5f}, u[3] = {0, 0, 1},
              v[3] = {1, 0, 0};
  memcpy(d.origin, origin, sizeof origin);
  memcpy(d.u, u, sizeof u);
  memcpy(d.v, v, sizeof v);
  d.point_mass = mass / (float)(n * n);
  d.k_stretch = ks;
  d.k_shear = kh;
  d.k_bend = kb;
  msocl_model *m = NULL;
  int rc = msocl_model_cloth_grid(&m, &d);
  if (rc != MSOCL_OK) {
    cli_fail(PROG, "building the cloth", rc);
    return NULL;
  }
  const float top[3] = {0, 0, 0};
  msocl_model_add_table(m, top, 0.35f, 0.3f);
  msocl_model_set_viscous_damping(m, 0.5f * d.point_mass);
  /* Half the largest stable step of symplectic Euler: the step is also
   * what collisions resolve, so it serves every integrator but explicit
   * Euler, whose own (smaller: the viscous damping alone bounds it) is
   * taken where it is smaller. */
  float own = 0.0f;
  if ((rc = msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, dt)) != MSOCL_OK ||
      (integrator == MSOCL_EXPLICIT_EULER &&
       (rc = msocl_stable_dt(m, MSOCL_EXPLICIT_EULER, &own)) != MSOCL_OK)) {
    cli_fail(PROG, "stable step", rc);
    msocl_model_destroy(m);
    return NULL;
  }
  if (integrator == MSOCL_EXPLICIT_EULER && own < *dt)
    *dt = own;
  *dt *= 0.5f;
  return m;
}

/* The command line: the scene's size and run, and the simulation options. */
typedef struct {
  int n, steps, per_call, ply;
  const char *spec, *out;
  int integrator, layout, math, strain;
  msocl_sim_options o;
} args;

/* Fills *a from argv. 0, or the exit status: 0 after -h (*done set), 2
 * after a message. */
static int parse(int argc, char **argv, args *a, int *done)
{
  int opt, rc = 0;
  *done = 0;
  if ((rc = cli_long_options(PROG, OPTIONS, argc, argv, done)) || *done)
    return rc ? rc : usage();
  msocl_sim_options *o = &a->o;
  opterr = 0;
  while (!rc && (opt = getopt(argc, argv, OPTIONS)) != -1) {
    switch (opt) {
    case 'n': /* the cloth builder's most: its ~6 n^2 springs' ends index
               * with an int */
      rc = cli_int(PROG, opt, optarg, "grid size", 2, 13378, &a->n);
      break;
    case 's':
      rc = cli_int(PROG, opt, optarg, "steps", 0, INT_MAX, &a->steps);
      break;
    case 'd': a->spec = optarg; break;
    case 'o': a->out = optarg; break;
    case 'l':
      rc = cli_pick(PROG, opt, optarg, "layout", cli_layouts, 5, &a->layout);
      break;
    case 'm':
      rc = cli_pick(PROG, opt, optarg, "math mode", maths, 2, &a->math);
      break;
    case 'i':
      rc = cli_pick(PROG, opt, optarg, "integrator", cli_integrators, 5,
                    &a->integrator);
      break;
    case 'S':
      rc = cli_pick(PROG, opt, optarg, "strain limiting", strains, 3,
                    &a->strain);
      break;
    case 'p':
      rc = cli_int(PROG, opt, optarg, "parts", -1, MSOCL_MAX_DEVICES,
                   &o->tuning.ndevices);
      break;
    case 'c':
      rc = cli_int(PROG, opt, optarg, "calibration steps", 0, INT_MAX,
                   &o->tuning.calibrate_steps);
      break;
    case 'k':
      rc = cli_int(PROG, opt, optarg, "steps a call", 0, INT_MAX,
                   &a->per_call);
      break;
    case 'I':
      rc = cli_int(PROG, opt, optarg, "sweeps", 1, 1000,
                   &o->strain_iterations);
      break;
    case 'f': o->tuning.fused = MSOCL_ON; break;
    case 'O': o->tuning.overlap = MSOCL_OFF; break;
    case 'C': o->tuning.classes = MSOCL_ON; break;
    case 'V': o->tuning.classes = MSOCL_OFF; break;
    case 'h': *done = 1; return usage();
    default: return cli_bad_option(PROG, opt);
    }
  }
  if (!rc)
    rc = cli_no_operands(PROG, optind, argc, argv);
  if (!rc)
    rc = cli_output(PROG, a->out, &a->ply);
  o->tuning.layout = (msocl_layout)a->layout;
  o->math = (msocl_math)a->math;
  o->integrator = (msocl_integrator)a->integrator;
  o->strain = (msocl_strain)a->strain;
  return rc;
}

int main(int argc, char **argv)
{
  args a = {.n = 64, .steps = 2000, .out = "tablecloth.obj"};
  msocl_sim_options_init(&a.o);
  int done, status = parse(argc, argv, &a, &done);
  if (status || done)
    return status;
  int n = a.n, steps = a.steps, per_call = a.per_call, in = a.integrator;
  int strain = a.strain;
  const char *spec = a.spec, *out = a.out;
  msocl_sim_options o = a.o;

  msocl_runtime *rt = NULL;
  int rc = msocl_runtime_create(&rt, spec);
  if (rc != MSOCL_OK)
    return cli_fail(PROG, "choosing a device", rc);
  msocl_model *m = build(n, in, &o.dt);
  if (!m) {
    msocl_runtime_destroy(rt);
    return 1;
  }
  msocl_sim *s = NULL;
  double t0 = cli_now();
  rc = msocl_sim_create(&s, rt, m, &o);
  double t1 = cli_now();
  if (rc != MSOCL_OK) {
    msocl_model_destroy(m);
    msocl_runtime_destroy(rt);
    return cli_fail(PROG, "setting up the simulation", rc);
  }
  msocl_device_info info;
  msocl_layout layout;
  msocl_sim_device_info(s, &info);
  msocl_sim_layout(s, &layout);
  int classes = 0;
  msocl_sim_connectivity(s, NULL, &classes);
  char sweeps[32] = "";
  if (strain)
    snprintf(sweeps, sizeof sweeps, " (%d sweep%s a step)",
             o.strain_iterations, o.strain_iterations == 1 ? "" : "s");
  printf("device: %s [%s]\nlayout: %s%s, math: %s, integrator: %s, strain "
         "limiting: %s%s\n",
         info.name, info.platform_name,
         layout == MSOCL_LAYOUT_IMAGE2D  ? "image2d"
         : layout == MSOCL_LAYOUT_EDGES ? "edges"
         : layout == MSOCL_LAYOUT_GRID  ? "grid"
                                        : "buffer",
         classes > 0 ? " (spring classes)" : "",
         o.math == MSOCL_MATH_RELAXED ? "relaxed" : "precise",
         cli_integrators[in], strains[strain], sweeps);
  printf("grid %dx%d, %d steps of %.3g s (setup %.3f s)\n", n, n, steps,
         (double)o.dt, t1 - t0);
  msocl_split_info split;
  msocl_sim_split_info(s, &split);
  for (int d = 0; split.parts > 1 && d < split.parts; d++)
    printf("part %d: device %d, weight %.3g, points [%d, %d), %.0f first\n",
           d, split.device[d], (double)split.weight[d], split.first[d],
           split.first[d] + split.count[d], split.boundary_points[d]);

  /* The first step, untimed, keeps first-launch costs out of the timing
   * (the mesh written is `steps` on, none for -s 0). */
  double secs = 0.0;
  const int timed = steps > 0 ? steps - 1 : 0;
  cli_progress p;
  cli_progress_start(&p, timed);
  rc = msocl_sim_step(s, steps > 0);
  if (rc == MSOCL_OK)
    rc = cli_step(s, &p, timed, per_call, &secs);
  cli_progress_end(&p);
  float *xyz = malloc(3 * (size_t)n * n * sizeof *xyz);
  float *nrm = malloc(3 * (size_t)n * n * sizeof *nrm);
  if (rc == MSOCL_OK && (!xyz || !nrm))
    rc = MSOCL_ERR_NO_MEMORY;
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_positions(s, xyz);
  if (rc == MSOCL_OK)
    rc = msocl_sim_read_normals(s, nrm);
  int ntri = 0;
  const int *tri = NULL;
  if (rc == MSOCL_OK)
    rc = msocl_model_triangles(m, &ntri, &tri);
  if (rc == MSOCL_OK)
    rc = cli_write_mesh(out, a.ply, n * n, xyz, nrm, ntri, tri);
  if (rc == MSOCL_OK) {
    printf("%.3f s: %.1f steps/s, %.3g vertex-steps/s", secs,
           secs > 0 ? timed / secs : 0.0,
           secs > 0 ? (double)timed * n * n / secs : 0.0);
    if (per_call > 0 && per_call < steps)
      printf(" (%d steps a call)", per_call);
    printf("\n");
    if (split.parts > 1) {
      msocl_sim_split_info(s, &split);
      printf("exchange: %.0f bytes a step through the host\n",
             split.bytes_per_step);
      for (int d = 0; d < split.parts; d++)
        printf("  part %d (device %d, %d points): host %.3f s in transfers, "
               "%.3f s waiting for the device; device %.3f s in kernels, "
               "%.3g s in copies (%.3g s of them beside the interior)\n",
               d, split.device[d], split.count[d],
               split.part_exchange_seconds[d], split.part_wait_seconds[d],
               split.compute_seconds[d], split.copy_seconds[d],
               split.hidden_copy_seconds[d]);
    }
    printf("wrote %s\n", out);
  } else {
    cli_fail(PROG, "simulating", rc);
  }
  free(xyz);
  free(nrm);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
  return rc == MSOCL_OK ? 0 : 1;
}
