/* Writes frames as Wavefront OBJ with optional vertex normals. */
#include "config.h"
#include "internal.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

int msocl_write_obj(const char *path, int npoints, const float *xyz,
                    const float *normals, int ntriangles, const int *ijk)
{
  msocl__clear_error();
  int rc = msocl__frame_check(path, npoints, xyz, normals, ntriangles, ijk);
  if (rc != MSOCL_OK)
    return rc;
  char tmp[4096];
  FILE *f = msocl__frame_open(path, tmp, sizeof tmp);
  if (!f)
    return MSOCL_ERR_IO;
  fprintf(f, "# libmsocl frame: %d points, %d triangles\n", npoints,
          ntriangles);
  for (int i = 0; i < npoints; i++)
    fprintf(f, "v %.9g %.9g %.9g\n", xyz[3 * i], xyz[3 * i + 1],
            xyz[3 * i + 2]);
  if (normals)
    for (int i = 0; i < npoints; i++)
      fprintf(f, "vn %.6g %.6g %.6g\n", normals[3 * i], normals[3 * i + 1],
              normals[3 * i + 2]);
  for (int t = 0; t < ntriangles; t++) {
    int a = ijk[3 * t] + 1, b = ijk[3 * t + 1] + 1, c = ijk[3 * t + 2] + 1;
    if (normals)
      fprintf(f, "f %d//%d %d//%d %d//%d\n", a, a, b, b, c, c);
    else
      fprintf(f, "f %d %d %d\n", a, b, c);
  }
  return msocl__frame_close(f, path, tmp);
}
