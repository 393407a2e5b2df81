/* Creating a simulation: checking the options, splitting the model into
 * one range of points a device, and planning which points each device
 * must receive from the others every step. */
#include "config.h"
#include "sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* An msocl_choice field: AUTO, ON or OFF. */
static int check_choice(msocl_choice c, const char *name)
{
  if (c != MSOCL_AUTO && c != MSOCL_ON && c != MSOCL_OFF)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "tuning.%s is %d: MSOCL_AUTO, MSOCL_ON or MSOCL_OFF",
                       name, (int)c);
  return MSOCL_OK;
}

static int check_options(const msocl_runtime *rt, const msocl_sim_options *o)
{
  const msocl_tuning *t = &o->tuning;
  MSOCL__TRY(msocl__check_physics(o));
  if (t->layout < MSOCL_LAYOUT_AUTO || t->layout > MSOCL_LAYOUT_GRID)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown layout %d",
                       (int)t->layout);
  if (t->device < 0 || t->device >= rt->ndev)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "device %d out of range: the runtime holds %d",
                       t->device, rt->ndev);
  if (t->ndevices < 0 && t->ndevices != MSOCL_ALL_DEVICES)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "ndevices %d: a count of devices (0 or 1: one) or "
                       "MSOCL_ALL_DEVICES (%d)",
                       t->ndevices, MSOCL_ALL_DEVICES);
  int parts = t->ndevices < 0 ? rt->ndev - t->device
                              : t->ndevices == 0 ? 1 : t->ndevices;
  if (t->device + parts > rt->ndev || parts > MSOCL_MAX_DEVICES)
    return msocl__fail(MSOCL_ERR_BAD_INDEX,
                       "devices %d to %d asked for: the runtime holds %d",
                       t->device, t->device + parts - 1, rt->ndev);
  for (int d = 0; d < parts && d < MSOCL_MAX_DEVICES; d++)
    if (!(t->weights[d] >= 0.0f) || !isfinite(t->weights[d]))
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "weight %d is %g: weights must be finite and >= 0",
                         d, t->weights[d]);
  if (parts > 1 && t->layout == MSOCL_LAYOUT_EDGES)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "the EDGES layout runs on one device, not split over "
                       "%d: use BUFFER (in precise math EDGES gives its "
                       "result bit for bit)",
                       parts);
  if (parts > 1 && o->strain != MSOCL_STRAIN_NONE)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "a model split over %d devices runs the gather layouts "
                       "without strain limiting (strain sweeps run on one "
                       "device)",
                       parts);
  if (o->strain == MSOCL_STRAIN_VELOCITY &&
      o->integrator != MSOCL_SYMPLECTIC_EULER &&
      o->integrator != MSOCL_IMPLICIT_EULER)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "velocity strain limiting needs an integrator whose "
                       "position update uses the new velocity (symplectic "
                       "or implicit Euler)");
  if (t->layout == MSOCL_LAYOUT_EDGES &&
      (o->integrator != MSOCL_SYMPLECTIC_EULER ||
       o->strain != MSOCL_STRAIN_NONE))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "the EDGES layout runs symplectic Euler without strain "
                       "limiting; use BUFFER for other methods");
  int rc = check_choice(t->fused, "fused");
  if (rc == MSOCL_OK)
    rc = check_choice(t->overlap, "overlap");
  if (rc == MSOCL_OK)
    rc = check_choice(t->classes, "classes");
  if (rc == MSOCL_OK)
    rc = check_choice(t->renumber, "renumber");
  if (rc != MSOCL_OK)
    return rc;
  if (t->fused == MSOCL_ON && (o->integrator != MSOCL_SYMPLECTIC_EULER ||
                               t->layout == MSOCL_LAYOUT_EDGES ||
                               o->strain == MSOCL_STRAIN_VELOCITY))
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "fused runs symplectic Euler's two passes on a gather "
                       "layout, without velocity strain limiting (which "
                       "works between the passes)");
  if (t->buffer_slots < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "buffer_slots is %d: >= 0",
                       t->buffer_slots);
  if (t->sweep_steps < 0 || t->sweep_steps > MSOCL_MAX_SWEEP_STEPS)
    return msocl__fail(MSOCL_ERR_BAD_VALUE,
                       "sweep_steps is %d: 1 to %d, or 0 to choose",
                       t->sweep_steps, MSOCL_MAX_SWEEP_STEPS);
  if (t->calibrate_steps < 0)
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "calibrate_steps %d is negative",
                       t->calibrate_steps);
  return MSOCL_OK;
}

/* Mass, size and springs of the scene: the blow-up check's energy scale. */
static void scene_scale(msocl_sim *s, const msocl_model *m)
{
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY,
                                                         -INFINITY,
                                                         -INFINITY};
  s->total_mass = 0.0;
  for (int i = 0; i < m->n; i++) {
    s->total_mass += m->mass[i];
    for (int c = 0; c < 3; c++) {
      double x = m->pos[3 * i + c];
      lo[c] = x < lo[c] ? x : lo[c];
      hi[c] = x > hi[c] ? x : hi[c];
    }
  }
  double d2 = 0.0;
  for (int c = 0; c < 3; c++)
    d2 += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  s->extent = sqrt(d2);
  /* the scale's floor: every spring stretched by 1e-3 of its rest length */
  s->efloor = 0.0;
  for (int t = 0; t < m->ns; t++)
    s->efloor += 0.5 * m->k[t] * 1e-6 * (double)m->rest[t] * m->rest[t];
}



/* Weighs each device by its speed: the whole model for `steps` steps on
 * it alone, after the same steps untimed (PoCL compiles a kernel at its
 * first launch, and a run of several steps launches kernels one step
 * does not: GRID's sweep), and the faster of two timed runs (noise only
 * slows). */
static int calibrate(msocl_sim *s, msocl_runtime *rt, const msocl_model *m,
                     const msocl_sim_options *split)
{
  msocl_sim_options o = *split; /* as the split's engines will run */
  o.check_every = 0;
  for (int d = 0; d < s->nparts; d++) {
    msocl__engine *e = NULL;
    struct msocl__device *dev = &rt->dev[o.tuning.device + d];
    int rc = msocl__engine_create(&e, dev, m, &o, 0, m->n);
    double t = INFINITY;
    for (int run = 0; run < 3 && rc == MSOCL_OK; run++) {
      const double t0 = msocl__seconds();
      rc = msocl__integrate(e, o.tuning.calibrate_steps);
      if (rc == MSOCL_OK && clFinish(e->dev->queue) != CL_SUCCESS)
        rc = msocl__fail(MSOCL_ERR_INVALID_ARG, "calibration failed");
      const double took = msocl__seconds() - t0;
      if (run > 0 && took < t)
        t = took;
    }
    msocl__engine_destroy(e);
    if (rc != MSOCL_OK)
      return rc;
    s->o.tuning.weights[d] = (float)(1.0 / (t > 1e-9 ? t : 1e-9));
  }
  return MSOCL_OK;
}

/* Contiguous ranges sized by the weights (all 0: equal). */
static int partition(msocl_sim *s, const msocl_model *m, int calibrated)
{
  double w[MSOCL__MAX_PARTS], total = 0.0;
  for (int d = 0; d < s->nparts; d++)
    total += (w[d] = s->o.tuning.weights[d]);
  if (!(total > 0.0))
    for (int d = 0; d < s->nparts; d++)
      total += (w[d] = 1.0);
  /* Implicit Euler's CG sums work-group partials: ranges that start at
   * multiples of 64 keep the groups, and so the sums, of one device. */
  const int align = s->o.integrator == MSOCL_IMPLICIT_EULER ? 64 : 1;
  double cum = 0.0;
  int lo = 0;
  for (int d = 0; d < s->nparts; d++) {
    cum += w[d];
    int hi = d == s->nparts - 1
                 ? m->n
                 : align * (int)llround(m->n * (cum / total) / align);
    if (hi <= lo)
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "device %d would get no points of %d (%s too "
                         "uneven, or fewer points than devices%s)",
                         d, m->n,
                         calibrated ? "the weights calibrate_steps measured "
                                      "(its speed against the others')"
                                    : "weights",
                         align > 1 ? "; implicit Euler splits in whole "
                                     "work-groups of 64 points"
                                   : "");
    s->halo[d][d][0] = lo;
    s->halo[d][d][1] = hi;
    lo = hi;
  }
  return MSOCL_OK;
}

/* For every pair, the span of e's points that d's springs reach: any
 * split is correct, even one whose ranges are narrower than a spring's
 * reach (the span then covers several devices' ranges). */
static void plan_halos(msocl_sim *s, const msocl_model *m)
{
  int owner_lo[MSOCL__MAX_PARTS], owner_hi[MSOCL__MAX_PARTS];
  for (int d = 0; d < s->nparts; d++) {
    owner_lo[d] = s->halo[d][d][0];
    owner_hi[d] = s->halo[d][d][1];
    for (int e = 0; e < s->nparts; e++)
      if (e != d) {
        s->halo[d][e][0] = m->n;
        s->halo[d][e][1] = 0;
      }
  }
  for (int sp = 0; sp < m->ns; sp++)
    for (int end = 0; end < 2; end++) {
      int i = m->ij[2 * sp + end], j = m->ij[2 * sp + 1 - end], d = 0, e = 0;
      while (i >= owner_hi[d])
        d++;
      while (j >= owner_hi[e])
        e++;
      if (d == e)
        continue;
      int *h = s->halo[d][e];
      h[0] = j < h[0] ? j : h[0];
      h[1] = j + 1 > h[1] ? j + 1 : h[1];
    }
  (void)owner_lo;
}

/* Mean |i - j| over the springs, the points numbered new[old] (NULL:
 * as they are). The mean, not the largest: one hub point (a solid's
 * centre) reaches across any numbering, but the rest still gain. */
static double mean_reach(const msocl_model *m, const int *num)
{
  double sum = 0.0;
  for (int sp = 0; sp < m->ns; sp++) {
    int i = m->ij[2 * sp], j = m->ij[2 * sp + 1];
    if (num) {
      i = num[i];
      j = num[j];
    }
    sum += i > j ? i - j : j - i;
  }
  return m->ns > 0 ? sum / m->ns : 0.0;
}

/* The model the engines run: m itself, or m renumbered by reverse
 * Cuthill-McKee where that brings spring neighbours closer (s->perm
 * records how). A cloth grid or lattice keeps its numbering: row by row
 * (layer by layer) it is banded already, and the GRID layout derives
 * neighbours from it; one built by hand runs as a copy carrying the
 * builder's record. */
static int number_points(msocl_sim *s, const msocl_model *m,
                         msocl_model **renumbered)
{
  *renumbered = NULL;
  if (msocl__grid_intact(m))
    return MSOCL_OK;
  /* a grid built by hand, for AUTO or GRID: run as the builder's */
  struct msocl__grid g;
  if ((s->o.tuning.layout == MSOCL_LAYOUT_AUTO || s->o.tuning.layout == MSOCL_LAYOUT_GRID) &&
      msocl__grid_detect(m, &g))
    return msocl__model_with_grid(m, &g, renumbered);
  if (s->o.tuning.renumber == MSOCL_OFF || m->n < 3)
    return MSOCL_OK;
  int *perm = malloc((size_t)m->n * sizeof *perm),
      *num = malloc((size_t)m->n * sizeof *num);
  int rc = perm && num ? msocl__order_rcm(m, perm, NULL, NULL)
                       : msocl__fail(MSOCL_ERR_NO_MEMORY, "point numbering");
  if (rc == MSOCL_OK) {
    for (int k = 0; k < m->n; k++)
      num[perm[k]] = k;
    if (mean_reach(m, num) < mean_reach(m, NULL))
      rc = msocl__model_permuted(m, perm, renumbered);
  }
  free(num);
  if (*renumbered)
    s->perm = perm;
  else
    free(perm);
  return rc;
}

int msocl_sim_create(msocl_sim **out, msocl_runtime *rt,
                     const msocl_model *model, const msocl_sim_options *opts)
{
  msocl__clear_error();
  if (!out)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim out-pointer is NULL");
  *out = NULL;
  if (!rt || !model)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "%s is NULL",
                       rt ? "model" : "runtime");
  msocl_sim_options o;
  msocl_sim_options_init(&o);
  if (opts)
    o = *opts;
  int rc = check_options(rt, &o);
  if (rc == MSOCL_OK)
    rc = msocl_model_validate(model);
  /* before renumbering, so an error names the caller's point */
  if (rc == MSOCL_OK)
    rc = msocl__layout_fits(model, o.tuning.layout);
  if (rc != MSOCL_OK)
    return rc;
  msocl_sim *s = calloc(1, sizeof *s);
  if (!s)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
  s->o = o;
  if ((rc = msocl__live_join(model, &s->live)) != MSOCL_OK) {
    free(s);
    return rc;
  }
  msocl_model *renumbered = NULL;
  if ((rc = number_points(s, model, &renumbered)) != MSOCL_OK) {
    msocl_sim_destroy(s);
    return rc;
  }
  const msocl_model *m = renumbered ? renumbered : model;
  s->n = m->n;
  const msocl_tuning *t = &o.tuning;
  s->nparts = t->ndevices < 0 ? rt->ndev - t->device
                              : t->ndevices == 0 ? 1 : t->ndevices;
  scene_scale(s, m);
  s->stage = malloc(3 * (size_t)m->n * sizeof(float));
  s->pinned = malloc((size_t)m->n);
  if (!s->stage || !s->pinned) {
    msocl_model_destroy(renumbered);
    msocl_sim_destroy(s);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
  }
  memcpy(s->pinned, m->pinned, (size_t)m->n);
  int weighed = 0;
  for (int d = 0; d < s->nparts; d++)
    weighed |= t->weights[d] > 0.0f;
  const int calibrated = s->nparts > 1 && !weighed && t->calibrate_steps > 0;
  if (calibrated)
    rc = calibrate(s, rt, m, &o);
  if (rc == MSOCL_OK)
    rc = partition(s, m, calibrated);
  if (rc == MSOCL_OK)
    plan_halos(s, m);
  for (int d = 0; rc == MSOCL_OK && d < s->nparts; d++) {
    rc = msocl__engine_create(&s->part[d],
                              (struct msocl__device *)&rt->dev[t->device + d],
                              m, &o, s->halo[d][d][0], s->halo[d][d][1]);
    /* the exchange copies one state layout: every engine runs the first
     * one's connectivity */
    if (rc == MSOCL_OK && d == 0 && s->nparts > 1)
      o.tuning.layout = s->part[0]->lay.kind;
  }
  if (rc == MSOCL_OK)
    rc = msocl__meshes_create(s, model);
  if (rc == MSOCL_OK && s->nparts > 1)
    rc = msocl__exchange_plan(s);
  if (rc == MSOCL_OK && s->nparts > 1)
    rc = msocl__workers_create(&s->workers, s->nparts);
  msocl_model_destroy(renumbered); /* the engines hold copies */
  if (rc != MSOCL_OK) {
    msocl_sim_destroy(s);
    return rc;
  }
  *out = s;
  return MSOCL_OK;
}

void msocl_sim_destroy(msocl_sim *s)
{
  if (!s)
    return;
  msocl__workers_destroy(s->workers);
  msocl__exchange_free(s);
  for (int d = 0; d < s->nparts; d++)
    msocl__engine_destroy(s->part[d]);
  free(s->stage);
  free(s->pinned);
  free(s->perm);
  msocl__controls_free(s);
  msocl__soft_pins_free(s);
  msocl__colliders_free(s);
  msocl__meshes_free(s);
  msocl__live_leave(s->live);
  free(s);
}
