/* The paper's scene: a square tablecloth falls onto a round table. Prints
 * steps per second and writes the final mesh as OBJ.
 *
 *   tablecloth [-n GRID] [-s STEPS] [-d DEVICE_SPEC] [-l auto|image2d|buffer|edges|grid]
 *              [-m precise|relaxed] [-i symplectic|explicit|verlet|rk4|implicit]
 *              [-S none|provot|velocity [-I SWEEPS]] [-p PARTS [-c STEPS]] [-f]
 *              [-o OUT.obj]
 */
#include <msocl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int usage(const char *argv0)
{
  fprintf(stderr,
          "usage: %s [-n GRID] [-s STEPS] [-d DEVICE_SPEC] "
          "[-l auto|image2d|buffer|edges|grid] [-m precise|relaxed]\n"
          "  [-i symplectic|explicit|verlet|rk4|implicit] "
          "[-S none|provot|velocity [-I SWEEPS]] [-p PARTS [-c STEPS] [-O]] "
          "[-f] [-C|-V] "
          "[-P|-F] [-k STEPS] "
          "[-o OUT.obj]\n"
          "  -I: strain limiting's sweeps a step (default 10)\n"
          "  -p: split the cloth over PARTS of the chosen devices (-1: all)\n"
          "  -c: weigh the devices by a calibration run of STEPS steps\n"
          "  -O: split, all kernels then all copies (default: the points\n"
          "      other devices read first, their copies beside the rest)\n"
          "  -f: both passes of a step in one kernel (same result)\n"
          "  -C, -V: BUFFER with a spring-class byte in every slot, or with\n"
          "      rest length and stiffness in every slot (default: the\n"
          "      library's choice; same result)\n"
          "  -P, -F: GRID with the state in x, y, z planes, or in float4\n"
          "      (default: planes on a CPU device; same result)\n"
          "  -k: steps a msocl_sim_step call, as a frame loop (default: all\n"
          "      in one call)\n",
          argv0);
  return 2;
}

/* Index of `word` in `names` (count n), or -1. */
static int pick(const char *word, const char *const *names, int n)
{
  for (int i = 0; i < n; i++)
    if (!strcmp(word, names[i]))
      return i;
  return -1;
}

static const char *const integrators[] = {"symplectic", "explicit", "verlet",
                                          "rk4", "implicit"};
static const char *const strains[] = {"none", "provot", "velocity"};

static int fail(const char *what, int rc)
{
  fprintf(stderr, "tablecloth: %s: %s (%s)\n%s\n", what, msocl_strerror(rc),
          msocl_err_name(rc), msocl_last_error());
  return 1;
}

/* The tablecloth: 1 m square, 0.5 kg, 5 cm above a table of radius 0.35 m;
 * spring stiffness per type as in the paper's three spring kinds. */
static msocl_model *build(int n, float *dt)
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
    fail("building the cloth", rc);
    return NULL;
  }
  const float top[3] = {0, 0, 0};
  msocl_model_add_table(m, top, 0.35f, 0.3f);
  msocl_model_set_viscous_damping(m, 0.5f * d.point_mass);
  /* Half the largest stable step of symplectic Euler: the step is also
   * what collisions resolve, so the same dt serves every integrator. */
  if ((rc = msocl_stable_dt(m, MSOCL_SYMPLECTIC_EULER, dt)) != MSOCL_OK) {
    fail("stable step", rc);
    msocl_model_destroy(m);
    return NULL;
  }
  *dt *= 0.5f;
  return m;
}

int main(int argc, char **argv)
{
  int n = 64, steps = 2000, opt;
  const char *spec = NULL, *out = "tablecloth.obj";
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  int in = 0, strain = 0, per_call = 0;
  while ((opt = getopt(argc, argv, "n:s:d:l:m:o:i:S:I:p:c:k:fOCVPFh")) != -1) {
    switch (opt) {
    case 'n': n = atoi(optarg); break;
    case 's': steps = atoi(optarg); break;
    case 'd': spec = optarg; break;
    case 'o': out = optarg; break;
    case 'l':
      if (!strcmp(optarg, "image2d")) o.layout = MSOCL_LAYOUT_IMAGE2D;
      else if (!strcmp(optarg, "buffer")) o.layout = MSOCL_LAYOUT_BUFFER;
      else if (!strcmp(optarg, "edges")) o.layout = MSOCL_LAYOUT_EDGES;
      else if (!strcmp(optarg, "grid")) o.layout = MSOCL_LAYOUT_GRID;
      else if (!strcmp(optarg, "auto")) o.layout = MSOCL_LAYOUT_AUTO;
      else return usage(argv[0]);
      break;
    case 'm':
      if (!strcmp(optarg, "relaxed")) o.math = MSOCL_MATH_RELAXED;
      else if (!strcmp(optarg, "precise")) o.math = MSOCL_MATH_PRECISE;
      else return usage(argv[0]);
      break;
    case 'i':
      if ((in = pick(optarg, integrators, 5)) < 0) return usage(argv[0]);
      o.integrator = (msocl_integrator)in;
      break;
    case 'p': o.ndevices = atoi(optarg); break;
    case 'c': o.calibrate_steps = atoi(optarg); break;
    case 'k': per_call = atoi(optarg); break;
    case 'I': o.strain_iterations = atoi(optarg); break;
    case 'f': o.fused = 1; break;
    case 'O': o.overlap = 0; break;
    case 'C': o.classes = 1; break;
    case 'V': o.classes = 0; break;
    case 'P': o.planes = 1; break;
    case 'F': o.planes = 0; break;
    case 'S':
      if ((strain = pick(optarg, strains, 3)) < 0) return usage(argv[0]);
      o.strain = (msocl_strain)strain;
      break;
    default: return usage(argv[0]);
    }
  }
  if (n < 2 || steps < 0 || per_call < 0)
    return usage(argv[0]);
  if (per_call == 0)
    per_call = steps > 0 ? steps : 1;

  msocl_runtime *rt = NULL;
  int rc = msocl_runtime_create(&rt, spec);
  if (rc != MSOCL_OK)
    return fail("choosing a device", rc);
  msocl_model *m = build(n, &o.dt);
  if (!m) {
    msocl_runtime_destroy(rt);
    return 1;
  }
  msocl_sim *s = NULL;
  double t0 = now();
  rc = msocl_sim_create(&s, rt, m, &o);
  double t1 = now();
  if (rc != MSOCL_OK) {
    msocl_model_destroy(m);
    msocl_runtime_destroy(rt);
    return fail("setting up the simulation", rc);
  }
  msocl_device_info info;
  msocl_layout layout;
  msocl_sim_device_info(s, &info);
  msocl_sim_layout(s, &layout);
  int classes = 0, planes = 0;
  msocl_sim_connectivity(s, NULL, &classes);
  msocl_sim_planes(s, &planes);
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
         classes > 0 ? " (spring classes)" : planes ? " (in planes)" : "",
         o.math == MSOCL_MATH_RELAXED ? "relaxed" : "precise",
         integrators[in], strains[strain], sweeps);
  printf("grid %dx%d, %d steps of %.3g s (setup %.3f s)\n", n, n, steps,
         (double)o.dt, t1 - t0);
  msocl_split_info split;
  msocl_sim_split_info(s, &split);
  for (int d = 0; split.parts > 1 && d < split.parts; d++)
    printf("part %d: device %d, weight %.3g, points [%d, %d), %.0f first\n",
           d, split.device[d], (double)split.weight[d], split.first[d],
           split.first[d] + split.count[d], split.boundary_points[d]);

  /* One warm-up step keeps first-launch costs out of the timing. */
  rc = msocl_sim_step(s, 1);
  double t2 = now();
  for (int done = 0; rc == MSOCL_OK && done < steps; done += per_call)
    rc = msocl_sim_step(s, steps - done < per_call ? steps - done : per_call);
  double t3 = now();
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
    rc = msocl_write_obj(out, n * n, xyz, nrm, ntri, tri);
  if (rc == MSOCL_OK) {
    double secs = t3 - t2;
    printf("%.3f s: %.1f steps/s, %.3g vertex-steps/s", secs,
           secs > 0 ? steps / secs : 0.0,
           secs > 0 ? (double)steps * n * n / secs : 0.0);
    if (per_call < steps)
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
    fail("simulating", rc);
  }
  free(xyz);
  free(nrm);
  msocl_sim_destroy(s);
  msocl_model_destroy(m);
  msocl_runtime_destroy(rt);
  return rc == MSOCL_OK ? 0 : 1;
}
