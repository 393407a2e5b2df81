/* A mesh collider read from a Wavefront OBJ file with the library's OBJ
 * reader (faces fanned into triangles). */
#include "config.h"
#include "internal.h"
#include "obj_parse.h"

#include <stdlib.h>

int msocl_model_add_mesh_collider_obj(msocl_model *m, const char *path,
                                      float thickness, float friction)
{
  msocl__clear_error();
  if (!m)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "mesh collider: model is NULL");
  if (!path)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "mesh collider: path is NULL");
  char *text = NULL;
  size_t len = 0;
  struct msocl__obj o;
  MSOCL__TRY(msocl__obj_read_file(path, MSOCL_OBJ_MAX_FILE_BYTES, &text, &len));
  int rc = msocl__obj_parse(&o, text, len);
  free(text);
  if (rc != MSOCL_OK)
    return msocl__fail(rc, "%s: %s", path, msocl_last_error());
  rc = msocl_model_add_mesh_collider(m, o.xyz, o.nv, o.tri, o.nt, thickness,
                                     friction);
  msocl__obj_free(&o);
  if (rc != MSOCL_OK)
    return msocl__fail(rc, "%s: %s", path, msocl_last_error());
  return MSOCL_OK;
}
