/* Analytic colliders added to a running simulation (msocl.h's "moving
 * colliders"): checked as the model's adders check theirs (their code,
 * model/colliders.c and collider_shapes.c), then put into a slot of the
 * collider table (sim_colliders.c). */
#include "config.h"
#include "sim.h"

_Static_assert(MSOCL_MAX_COLLIDERS == MSOCL__MAX_COLLIDERS,
               "msocl.h's limit is the collider table's");

/* The engine's checks, the slot the collider takes and its friction. */
static int begin(msocl_sim *s, const char *call, const char *kind,
                 float friction, int *slot)
{
  msocl__clear_error();
  if (!s)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "sim is NULL");
  MSOCL__TRY(msocl__colliders_slot(s, call, slot));
  return msocl__collider_friction(kind, *slot, friction);
}

static int finish(msocl_sim *s, int slot, const struct msocl__collider *c,
                  int *id)
{
  MSOCL__TRY(msocl__colliders_insert(s, slot, c));
  if (id)
    *id = slot;
  return MSOCL_OK;
}

int msocl_sim_add_plane(msocl_sim *s, const float normal[3], float offset,
                        float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(s, "msocl_sim_add_plane", "plane", friction, &slot));
  MSOCL__TRY(msocl__collider_plane(slot, normal, offset, friction, &c));
  return finish(s, slot, &c, id);
}

int msocl_sim_add_sphere(msocl_sim *s, const float centre[3], float radius,
                         float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(s, "msocl_sim_add_sphere", "sphere", friction, &slot));
  MSOCL__TRY(msocl__collider_round(slot, MSOCL__SPHERE, centre, radius,
                                   friction, &c));
  return finish(s, slot, &c, id);
}

int msocl_sim_add_table(msocl_sim *s, const float top[3], float radius,
                        float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(s, "msocl_sim_add_table", "table", friction, &slot));
  MSOCL__TRY(msocl__collider_round(slot, MSOCL__TABLE, top, radius, friction,
                                   &c));
  return finish(s, slot, &c, id);
}

int msocl_sim_add_capsule(msocl_sim *s, const float a[3], const float b[3],
                          float radius, float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(s, "msocl_sim_add_capsule", "capsule", friction, &slot));
  MSOCL__TRY(msocl__collider_capsule(slot, a, b, radius, friction, &c));
  return finish(s, slot, &c, id);
}

int msocl_sim_add_box(msocl_sim *s, const float centre[3],
                      const float rotation[4], const float half[3],
                      float friction, int *id)
{
  int slot;
  struct msocl__collider c;
  MSOCL__TRY(begin(s, "msocl_sim_add_box", "box", friction, &slot));
  MSOCL__TRY(msocl__collider_box(slot, centre, rotation, half, friction, &c));
  return finish(s, slot, &c, id);
}
