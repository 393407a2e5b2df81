/* Writes frames to files: ASCII PLY 1.0 with optional vertex normals. */
#include "config.h"
#include "internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Non-finite values would be written as "nan" or "inf", which no reader
 * (the library's own included) takes back: a blown-up state, refused. */
static int finite_points(const char *path, int npoints, const float *v,
                         const char *what)
{
  for (int i = 0; v && i < 3 * npoints; i++)
    if (!isfinite(v[i]))
      return msocl__fail(MSOCL_ERR_NOT_FINITE,
                         "%s not written: point %d: %s %d is %g", path,
                         i / 3, what, i % 3, v[i]);
  return MSOCL_OK;
}

/* The argument checks of every frame writer: handles, counts, indices,
 * finite points and normals. */
int msocl__frame_check(const char *path, int npoints, const float *xyz,
                       const float *normals, int ntriangles, const int *ijk)
{
  if (!path || !xyz || (ntriangles > 0 && !ijk))
    return msocl__fail(MSOCL_ERR_NULL_HANDLE, "path or array is NULL");
  if (npoints <= 0 || ntriangles < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT, "%d points, %d triangles",
                       npoints, ntriangles);
  for (int t = 0; t < 3 * ntriangles; t++)
    if (ijk[t] < 0 || ijk[t] >= npoints)
      return msocl__fail(MSOCL_ERR_BAD_INDEX,
                         "triangle %d: index %d out of range [0, %d)", t / 3,
                         ijk[t], npoints);
  /* no reader takes a triangle back that names a point twice (the
   * library's own refuses it: it has no area) */
  for (int t = 0; t < ntriangles; t++) {
    const int *k = ijk + 3 * t;
    if (k[0] == k[1] || k[1] == k[2] || k[0] == k[2])
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "%s not written: triangle %d names point %d twice",
                         path, t, k[0] == k[1] || k[0] == k[2] ? k[0] : k[1]);
  }
  int rc = finite_points(path, npoints, xyz, "coordinate");
  return rc == MSOCL_OK ? finite_points(path, npoints, normals, "normal")
                        : rc;
}

int msocl_write_ply(const char *path, int npoints, const float *xyz,
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
  fprintf(f, "ply\nformat ascii 1.0\ncomment libmsocl frame\n");
  fprintf(f, "element vertex %d\n", npoints);
  fprintf(f, "property float x\nproperty float y\nproperty float z\n");
  if (normals)
    fprintf(f, "property float nx\nproperty float ny\nproperty float nz\n");
  fprintf(f, "element face %d\n", ntriangles);
  fprintf(f, "property list uchar int vertex_indices\nend_header\n");
  for (int i = 0; i < npoints; i++) {
    fprintf(f, "%.9g %.9g %.9g", xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    if (normals)
      fprintf(f, " %.6g %.6g %.6g", normals[3 * i], normals[3 * i + 1],
              normals[3 * i + 2]);
    fputc('\n', f);
  }
  for (int t = 0; t < ntriangles; t++)
    fprintf(f, "3 %d %d %d\n", ijk[3 * t], ijk[3 * t + 1], ijk[3 * t + 2]);
  return msocl__frame_close(f, path, tmp);
}
