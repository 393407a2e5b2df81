/* A model's count of the simulations made from it and still alive
 * (internal.h's msocl__live): msocl_sim_create copies the model, so a
 * setter called on the model afterwards would change nothing they run;
 * the setters of what a running simulation can change (gravity, damping,
 * air, pins) refuse instead, naming the msocl_sim_ call that does it. */
#include "config.h"
#include "internal.h"

#include <stdatomic.h>
#include <stdlib.h>

struct msocl__live {
  atomic_int sims; /* live simulations */
  atomic_int refs; /* the model's one and each simulation's */
};

static void unref(struct msocl__live *l)
{
  if (l && atomic_fetch_sub(&l->refs, 1) == 1)
    free(l);
}

/* The model's block, made at its first simulation. Models are built on one
 * thread; simulations of one model made on several threads at once race
 * only here, so the block is published with a compare-and-swap. */
int msocl__live_join(const msocl_model *cm, struct msocl__live **out)
{
  msocl_model *m = (msocl_model *)cm; /* the count is not the model's value */
  struct msocl__live *l =
      atomic_load((_Atomic(struct msocl__live *) *)&m->live);
  if (!l) {
    struct msocl__live *mine = malloc(sizeof *mine);
    if (!mine)
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "simulation");
    atomic_init(&mine->sims, 0);
    atomic_init(&mine->refs, 1);
    struct msocl__live *expected = NULL;
    if (atomic_compare_exchange_strong(
            (_Atomic(struct msocl__live *) *)&m->live, &expected, mine))
      l = mine;
    else {
      free(mine);
      l = expected;
    }
  }
  atomic_fetch_add(&l->refs, 1);
  atomic_fetch_add(&l->sims, 1);
  *out = l;
  return MSOCL_OK;
}

void msocl__live_leave(struct msocl__live *l)
{
  if (!l)
    return;
  atomic_fetch_sub(&l->sims, 1);
  unref(l);
}

/* From msocl_model_destroy. */
void msocl__live_drop(msocl_model *m)
{
  unref(m->live);
  m->live = NULL;
}

int msocl__live_refuse(const msocl_model *m, const char *what,
                       const char *instead)
{
  const int n = m->live ? atomic_load(&m->live->sims) : 0;
  if (n <= 0)
    return MSOCL_OK;
  return msocl__fail(MSOCL_ERR_INVALID_ARG,
                     "%s: the model has %d live simulation%s, which copied "
                     "it when created and would not see the change; call %s "
                     "on the simulation instead",
                     what, n, n == 1 ? "" : "s", instead);
}
