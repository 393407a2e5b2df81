/* How long the default 32x32 cloth, pinned at points 0 and 31 and
 * undamped, survives a step: the step where the blow-up check (every 100
 * steps) or, with -r, the double-precision host reference first fails.
 *
 *   cc -std=c99 -Ilib bench/blowup.c -L.libs -lmsocl -lm \
 *      -Wl,-rpath,$PWD/.libs -o blowup
 *   ./blowup [-r] [-s] [-i integrator] [-l layout] factor steps
 *
 * factor scales msocl_stable_dt (the rest state's limit), or with -s
 * msocl_safe_dt; integrator and layout are the enums' numbers. Prints the
 * steps survived (or "ok" and the steps asked for). Results:
 * docs/STABILITY.md. */
#define _POSIX_C_SOURCE 200809L /* getopt */
#include "msocl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static int fail(const char *what)
{
  fprintf(stderr, "blowup: %s: %s\n", what, msocl_last_error());
  return 1;
}

int main(int argc, char **argv)
{
  int ref = 0, safe = 0, c;
  msocl_integrator in = MSOCL_SYMPLECTIC_EULER;
  msocl_layout layout = MSOCL_LAYOUT_AUTO;
  while ((c = getopt(argc, argv, "rsi:l:")) != -1) {
    if (c == 'r')
      ref = 1;
    else if (c == 's')
      safe = 1;
    else if (c == 'i')
      in = (msocl_integrator)atoi(optarg);
    else if (c == 'l')
      layout = (msocl_layout)atoi(optarg);
    else
      return 2;
  }
  if (argc - optind != 2) {
    fprintf(stderr, "usage: blowup [-r] [-s] [-i n] [-l n] factor steps\n");
    return 2;
  }
  double factor = atof(argv[optind]);
  long long steps = atoll(argv[optind + 1]);
  msocl_cloth_desc d;
  msocl_cloth_desc_init(&d);
  msocl_model *m = NULL;
  if (msocl_model_cloth_grid(&m, &d) != MSOCL_OK)
    return fail("cloth");
  msocl_model_pin(m, 0, 1);
  msocl_model_pin(m, 31, 1);
  float rest, base;
  if (msocl_stable_dt(m, in, &rest) != MSOCL_OK ||
      (safe ? msocl_safe_dt(m, in, &base) : msocl_stable_dt(m, in, &base)))
    return fail("stable step");
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  o.dt = (float)(factor * base);
  o.integrator = in;
  o.layout = layout;
  o.check_every = 100;
  printf("dt %.5g s = %.4f x stable_dt; ", o.dt, o.dt / rest);
  const int chunk = 100;
  if (ref) {
    /* the same test the device check makes, on the double state */
    msocl_reference *r = NULL;
    msocl_energy e0, e;
    if (msocl_reference_create(&r, m, &o) != MSOCL_OK)
      return fail("reference");
    msocl_reference_energy(r, &e0);
    double mass = 32 * 32 * d.point_mass, scale = mass * 9.81 * sqrt(2.0);
    for (long long s = 0; s < steps; s += chunk) {
      msocl_reference_step(r, chunk);
      msocl_reference_energy(r, &e);
      if (!isfinite(e.total) || e.total > e0.total + 100.0 * scale) {
        printf("reference blew up by step %lld\n", s + chunk);
        return 0;
      }
    }
    printf("reference ok %lld\n", steps);
    msocl_reference_destroy(r);
    msocl_model_destroy(m);
    return 0;
  }
  msocl_runtime *rt = NULL;
  msocl_sim *s = NULL;
  if (msocl_runtime_create(&rt, NULL) != MSOCL_OK)
    return fail("runtime");
  if (msocl_sim_create(&s, rt, m, &o) != MSOCL_OK)
    return fail("sim");
  for (long long k = 0; k < steps; k += 10000) {
    int n = steps - k < 10000 ? (int)(steps - k) : 10000;
    if (msocl_sim_step(s, n) == MSOCL_ERR_UNSTABLE) {
      long long at;
      msocl_sim_step_count(s, &at);
      printf("blew up between steps %lld and %lld\n", at, at + 100);
      return 0;
    }
  }
  printf("ok %lld\n", steps);
  msocl_sim_destroy(s);
  msocl_runtime_destroy(rt);
  msocl_model_destroy(m);
  return 0;
}
