/* Wind's one arithmetic, scalar or vector (wind.cl, planes_rows.cl). */
#ifndef MSOCL_WIND_H
#define MSOCL_WIND_H

/* A third of the force on a triangle of edges e1 = p1 - p0 and
 * e2 = p2 - p0 whose corners' velocities sum to s = (v0 + v1) + v2, from
 * air at velocity air.xyz, with coef.x = rho Cd / 2 and coef.y =
 * rho Cl / 2, into fx, fy, fz (declared here, of type T, with temporaries
 * named after `tag`; SEL(c, a, b) is c ? a : b for T): the one arithmetic
 * of every wind kernel, scalar or vector (planes_rows.cl), so that each
 * layout gets the same bits. With the unnormalised normal N = e1 x e2 =
 * 2 A n the area cancels: f = kd |N.u| u / 2 + kl (N.u) (|u|^2 N -
 * (N.u) u) / (2 |N| |u|) = a u + b N, one square root and one division
 * (two would be paired into a vector and stop PoCL vectorising the
 * kernel). Each component has its own shape, so that -O3's SLP
 * vectorizer does not pair the three into a vector either (wind.cl). */
#define MSOCL_WIND_FORCE(T, SEL, tag, e1x, e1y, e1z, e2x, e2y, e2z, sx, sy,   \
                         sz, air, coef, fx, fy, fz)                           \
  const T tag##nx = (e1y) * (e2z) - (e1z) * (e2y),                            \
          tag##ny = fma((e1z), (e2x), -((e1x) * (e2z))),                      \
          tag##nz = fma(-(e1y), (e2x), (e1x) * (e2y));                        \
  const float tag##third = 1.0f / 3.0f;                                       \
  const T tag##ux = (air).x - (sx) * tag##third,                              \
          tag##uy = fma((sy), -tag##third, (air).y),                          \
          tag##uz = -((sz) * tag##third - (air).z);                           \
  const T tag##nu = tag##nx * tag##ux + tag##ny * tag##uy + tag##nz * tag##uz;\
  const T tag##uu = tag##ux * tag##ux + tag##uy * tag##uy + tag##uz * tag##uz;\
  const T tag##root =                                                         \
      sqrt((tag##nx * tag##nx + tag##ny * tag##ny + tag##nz * tag##nz) *      \
           tag##uu);                                                          \
  const T tag##d = 0.5f * tag##third * (coef).x * fabs(tag##nu);              \
  const T tag##l =                                                            \
      SEL(tag##root > 0.0f,                                                   \
          0.5f * tag##third * (coef).y * tag##nu / tag##root, 0.0f);          \
  const T tag##a = tag##d - tag##l * tag##nu, tag##b = tag##l * tag##uu;      \
  const T fx = tag##a * tag##ux + tag##b * tag##nx;                           \
  const T fy = fma(tag##a, tag##uy, tag##b * tag##ny);                        \
  const T fz = fma(tag##b, tag##nz, tag##a * tag##uz)

#endif
