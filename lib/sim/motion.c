/* A stepping call that moves something along a path over its steps (pins
 * toward their targets, sim_controls.c; soft pins' anchors,
 * sim_soft_pins.c; colliders toward their poses, sim_colliders.c; mesh
 * colliders, sim_mesh.c, which also act after each step when they do not
 * move) runs one step at a time: before step j of the call's N, each mover
 * sits at j / N of its path and moves toward (j + 1) / N; after the last,
 * it is at its path's end. The fractions are computed in float as
 * (float)j / (float)N, so that a caller giving the same ends to N one-step
 * calls gets the same steps. */
#include "config.h"
#include "sim.h"

void msocl__motion_call(msocl_sim *s, int n)
{
  if (n > 0 && (msocl__pins_pending(s) || msocl__soft_pins_moving(s) ||
                msocl__colliders_pending(s) || msocl__meshes_active(s))) {
    s->call_n = n;
    s->call_j = 0;
  }
}

int msocl__motion_moving(const msocl_sim *s)
{
  return s->call_n > 0;
}

/* `n` steps of the call, which may come in batches (the blow-up check's):
 * the count of those done runs across them. */
int msocl__motion_steps(msocl_sim *s, int n)
{
  msocl__engine *e = s->part[0];
  MSOCL__TRY(msocl__planes_enter(e));
  const float N = (float)s->call_n;
  const int pins = msocl__pins_pending(s), soft = msocl__soft_pins_moving(s);
  const int cols = msocl__colliders_pending(s);
  const int meshes = msocl__meshes_active(s);
  if (meshes && s->call_j == 0 && n > 0)
    MSOCL__TRY(msocl__meshes_begin(s, s->call_n));
  for (int q = 0; q < n && s->call_j < s->call_n; q++) {
    const float f0 = (float)s->call_j / N;
    const float f1 = (float)(s->call_j + 1) / N;
    if (pins)
      MSOCL__TRY(msocl__pins_place(s, f0, f0, f1, s->call_j == 0));
    if (soft)
      msocl__soft_pins_place(s, f0);
    if (cols)
      MSOCL__TRY(msocl__colliders_place(s, f0, f1));
    MSOCL__TRY(msocl__integrate(e, 1));
    if (meshes)
      MSOCL__TRY(msocl__meshes_step(s, f0, f1));
    s->steps++;
    s->call_j++;
    if (s->call_j % 64 == 0)
      MSOCL__CL(clFlush(e->dev->queue));
  }
  if (s->call_j == s->call_n) {
    const float last = (float)(s->call_n - 1) / N;
    if (pins) {
      MSOCL__TRY(msocl__pins_place(s, 1.0f, last, 1.0f, 0));
      msocl__pins_done(s);
    }
    if (soft)
      msocl__soft_pins_place(s, 1.0f);
    if (cols)
      MSOCL__TRY(msocl__colliders_done(s));
    s->call_n = 0;
    if (meshes)
      MSOCL__TRY(msocl__meshes_end(s));
  }
  return MSOCL_OK;
}
