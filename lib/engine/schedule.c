/* Each integrator's step as a table of phases and passes (schedule.h),
 * and the walk of it on one engine; the split runtime (sim_step.c) walks
 * the same phases over several, exchanging after each what its mask
 * names. */
#include "config.h"
#include "schedule.h"

#define TRY MSOCL__TRY

enum {
  P = MSOCL__X_POS_W, V = MSOCL__X_VEL_W,
  S0 = MSOCL__X_STAGE0, SV0 = MSOCL__X_STAGEV0,
  S1 = MSOCL__X_STAGE1, SV1 = MSOCL__X_STAGEV1
};

#define PASS1(a) 1, {MSOCL__P_##a}
#define PASS2(a, b) 2, {MSOCL__P_##a, MSOCL__P_##b}

/* [integrator][strain]. Other engines read the new positions, and the
 * velocities when dashpots do; implicit Euler's right-hand side reads
 * neighbours' velocities (K v) even without. The strain limits the
 * options refuse (velocity strain beside explicit Euler, Verlet, RK4) run
 * as none. Verlet's Provot correction comes between drift and kick, on the
 * half-step velocities: the kick then keeps the corrected positions'
 * acceleration for the next step (after the kick, the next drift used the
 * acceleration of positions the correction had moved, and a hanging cloth
 * blew up at half the stable step). */
static const struct msocl__schedule table[5][3] = {
    [MSOCL_SYMPLECTIC_EULER] =
        {[MSOCL_STRAIN_NONE] = {2,
                                {{PASS1(VELOCITY), 0, 0},
                                 {PASS1(POSITION), P, V}}},
         [MSOCL_STRAIN_PROVOT] = {2,
                                  {{PASS1(VELOCITY), 0, 0},
                                   {PASS2(POSITION, PROVOT), P, V}}},
         [MSOCL_STRAIN_VELOCITY] = {2,
                                    {{PASS2(VELOCITY, STRAIN_VEL), 0, 0},
                                     {PASS1(POSITION), P, V}}}},
    [MSOCL_EXPLICIT_EULER] =
        {[MSOCL_STRAIN_NONE] = {1, {{PASS1(EULER), P, V}}},
         [MSOCL_STRAIN_PROVOT] = {1, {{PASS2(EULER, PROVOT), P, V}}},
         [MSOCL_STRAIN_VELOCITY] = {1, {{PASS1(EULER), P, V}}}},
    [MSOCL_VERLET] =
        {[MSOCL_STRAIN_NONE] = {2,
                                {{PASS1(DRIFT), P, MSOCL__X_VEL_R},
                                 {PASS1(KICK), 0, V}}},
         [MSOCL_STRAIN_PROVOT] = {2,
                                  {{PASS2(DRIFT, PROVOT_HALF), P,
                                    MSOCL__X_VEL_R},
                                   {PASS1(KICK), 0, V}}},
         [MSOCL_STRAIN_VELOCITY] = {2,
                                    {{PASS1(DRIFT), P, MSOCL__X_VEL_R},
                                     {PASS1(KICK), 0, V}}}},
    [MSOCL_RK4] = {[MSOCL_STRAIN_NONE] = {4,
                                          {{PASS1(RK4_0), S0, SV0},
                                           {PASS1(RK4_1), S1, SV1},
                                           {PASS1(RK4_2), S0, SV0},
                                           {PASS1(RK4_3), P, V}}},
                   [MSOCL_STRAIN_PROVOT] = {4,
                                            {{PASS1(RK4_0), S0, SV0},
                                             {PASS1(RK4_1), S1, SV1},
                                             {PASS1(RK4_2), S0, SV0},
                                             {PASS2(RK4_3, PROVOT), P, V}}},
                   [MSOCL_STRAIN_VELOCITY] = {4,
                                              {{PASS1(RK4_0), S0, SV0},
                                               {PASS1(RK4_1), S1, SV1},
                                               {PASS1(RK4_2), S0, SV0},
                                               {PASS1(RK4_3), P, V}}}},
    [MSOCL_IMPLICIT_EULER] =
        {[MSOCL_STRAIN_NONE] = {2,
                                {{PASS1(CG), 0, 0},
                                 {PASS1(POSITION), P | V, 0}}},
         [MSOCL_STRAIN_PROVOT] = {2,
                                  {{PASS1(CG), 0, 0},
                                   {PASS2(POSITION, PROVOT), P | V, 0}}},
         [MSOCL_STRAIN_VELOCITY] = {2,
                                    {{PASS2(CG, STRAIN_VEL), 0, 0},
                                     {PASS1(POSITION), P | V, 0}}}},
};

/* Symplectic Euler's two passes in one (options.tuning.fused), [strain]; the
 * velocity kind, which works between them, is refused. */
static const struct msocl__schedule fused[3] = {
    [MSOCL_STRAIN_NONE] = {1, {{PASS1(FUSED), P, V}}},
    [MSOCL_STRAIN_PROVOT] = {1, {{PASS2(FUSED, PROVOT), P, V}}},
    [MSOCL_STRAIN_VELOCITY] = {1, {{PASS1(FUSED), P, V}}},
};

const struct msocl__schedule *msocl__schedule_of(const msocl_sim_options *o)
{
  /* EDGES: symplectic Euler's two passes in one, as fused (its result is
   * the same, bit for bit) */
  const int one = o->tuning.fused == MSOCL_ON ||
                  o->tuning.layout == MSOCL_LAYOUT_EDGES;
  return one ? &fused[o->strain] : &table[o->integrator][o->strain];
}

int msocl__phase_count(const msocl__engine *s)
{
  return msocl__schedule_of(&s->o)->nphases;
}

unsigned msocl__phase_mask(const msocl__engine *s, int phase)
{
  const struct msocl__phase_desc *d =
      &msocl__schedule_of(&s->o)->phase[phase];
  return d->mask | (s->damped ? d->damped : 0);
}

static int run_pass(msocl__engine *s, enum msocl__pass p)
{
  if (p == MSOCL__P_CG)
    return msocl__implicit_cg(&s, 1, NULL, NULL);
  return msocl__planes_pass(s, p);
}

int msocl__phase(msocl__engine *s, int phase, unsigned *exchange)
{
  const struct msocl__phase_desc *d =
      &msocl__schedule_of(&s->o)->phase[phase];
  *exchange = msocl__phase_mask(s, phase);
  for (int q = 0; q < d->npasses; q++)
    TRY(run_pass(s, d->pass[q]));
  return MSOCL_OK;
}

void msocl__step_done(msocl__engine *s)
{
  msocl__planes_step_done(s);
}

int msocl__integrate(msocl__engine *s, int n)
{
  if (n <= 0)
    return MSOCL_OK;
  TRY(msocl__planes_enter(s));
  const int phases = msocl__phase_count(s);
  for (int q = 0; q < n;) {
    /* several steps a launch: one set flip, as it writes the other set */
    int done;
    TRY(msocl__pl_rows_steps(s, n - q, &done));
    if (done == 0) {
      TRY(msocl__wind_pass(s));
      TRY(msocl__field_pass(s));
      TRY(msocl__soft_pass(s));
      for (int ph = 0; ph < phases; ph++) {
        unsigned x;
        TRY(msocl__phase(s, ph, &x));
      }
      done = 1;
    }
    msocl__step_done(s);
    if (q / 64 != (q + done) / 64)
      MSOCL__CL(clFlush(s->dev->queue));
    q += done;
  }
  return MSOCL_OK;
}
