/* How many steps GRID's sweep runs a launch (planes_rows.c). More steps
 * read and write the planes fewer times but recompute more rows at the
 * blocks' edges and keep more rings of terms; where that balances depends
 * on the CPU's caches, which OpenCL does not report (PoCL gives the L3 as
 * the global memory cache), so AUTO times each candidate over the first
 * launches and keeps the fastest. Every count gives the same bits. */
#include "config.h"
#include "planes.h"

#include <math.h>

/* eight steps, faster on an AMD EPYC's 1 MB L2 at 1024²-2048², lost 14 %
 * here when chosen at 256² on a trial's noise: forced only */
static const int candidate[MSOCL__SWEEP_CANDIDATES] = {4, 3, 2};
#define CANDIDATES MSOCL__SWEEP_CANDIDATES
/* A trial: launches of one candidate back to back, as steps run when
 * chosen, over this many steps (a multiple of each); each candidate's
 * best of ROUNDS trials stands for it, as noise here only slows. */
#define TRIAL_STEPS 24
#define ROUNDS 3
/* launches outside trials (calls too short for one) before AUTO settles
 * on what it has timed */
#define PATIENCE 16

void msocl__sweep_steps_init(msocl__engine *s)
{
  s->pl_steps_k = s->o.tuning.sweep_steps;
  s->pl_trials = s->pl_trial_left = s->pl_untimed = 0;
  for (int c = 0; c < CANDIDATES; c++)
    s->pl_trial_s[c] = INFINITY;
}

/* The fastest candidate timed (four where none was). */
static void choose(msocl__engine *s)
{
  int best = 4;
  double t = INFINITY;
  for (int c = 0; c < CANDIDATES; c++)
    if (s->pl_trial_s[c] < t) {
      t = s->pl_trial_s[c];
      best = candidate[c];
    }
  s->pl_steps_k = best;
}

static int current(const msocl__engine *s)
{
  return candidate[(s->pl_trials - 1) % CANDIDATES];
}

int msocl__sweep_next(msocl__engine *s, int n, int *start, int *end)
{
  *start = *end = 0;
  if (n < 2)
    return 0;
  if (s->pl_steps_k)
    return n < s->pl_steps_k ? n : s->pl_steps_k;
  if (s->pl_trial_left > 0 && current(s) <= n) {
    *end = --s->pl_trial_left == 0;
    return current(s);
  }
  /* a trial cut short (a call that failed inside it) starts again */
  s->pl_trial_left = 0;
  /* the first launch builds PoCL's work-group function: not timed */
  const int plain = n < 4 ? n : 4;
  if (s->pl_trials == 0 || n < TRIAL_STEPS) {
    if (s->pl_trials == 0)
      s->pl_trials = 1;
    else if (++s->pl_untimed >= PATIENCE)
      choose(s);
    return plain;
  }
  const int k = current(s);
  s->pl_trial_left = TRIAL_STEPS / k - 1;
  *start = 1;
  *end = s->pl_trial_left == 0;
  return k;
}

void msocl__sweep_took(msocl__engine *s, double seconds)
{
  const int c = (s->pl_trials - 1) % CANDIDATES;
  if (seconds / TRIAL_STEPS < s->pl_trial_s[c])
    s->pl_trial_s[c] = seconds / TRIAL_STEPS;
  if (++s->pl_trials > CANDIDATES * ROUNDS)
    choose(s);
}
