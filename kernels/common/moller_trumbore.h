/* Ray/triangle test of Moeller & Trumbore (1997), "Fast, Minimum Storage Ray/Triangle
 * Intersection". Shared by the host and every kernel so all intersectors round alike.
 * No epsilon: det == 0 (ray in the triangle's plane) is rejected exactly, and a tiny det
 * that overflows 1/det yields inf/NaN barycentrics that fail the comparisons below.
 * The caller checks t against its own (tmin, best) interval; iterating triangles in
 * increasing global index with a strict '<' gives the tie rule (lowest index on equal t). */
#ifndef GRIDRT_MOLLER_TRUMBORE_H
#define GRIDRT_MOLLER_TRUMBORE_H
#include "gridrt_types.h"

/* n = e1 x e2, as the prepared triangles store it. */
GR_FN void gr_triangle_normal(float e1x, float e1y, float e1z, float e2x, float e2y, float e2z,
                              float* nx, float* ny, float* nz) {
  *nx = e1y * e2z - e1z * e2y;
  *ny = e1z * e2x - e1x * e2z;
  *nz = e1x * e2y - e1y * e2x;
}

/* The test given the triangle's normal n = e1 x e2. The paper's triple products, each
 * taken around the vector that the ray alone or the triangle alone decides: det =
 * e1.(d x e2) = -d.n, u = s.(d x e2) = e2.c, v = d.(s x e1) = -e1.c and t = e2.(s x e1) =
 * s.n, with s = o - v0 and c = s x d: 21 products a test instead of the paper's 27 (the
 * kernels' tests are bound by their products). */
GR_FN int gr_intersect_mt_normal(float ox, float oy, float oz, float dx, float dy, float dz,
                                 float v0x, float v0y, float v0z, float e1x, float e1y, float e1z,
                                 float e2x, float e2y, float e2z, float nx, float ny, float nz,
                                 float* t_out, float* u_out, float* v_out) {
  float det = -(dx * nx + dy * ny + dz * nz);
  float inv_det = 1.0f / det;
  float sx = ox - v0x;
  float sy = oy - v0y;
  float sz = oz - v0z;
  float cx = sy * dz - sz * dy;
  float cy = sz * dx - sx * dz;
  float cz = sx * dy - sy * dx;
  float u = (e2x * cx + e2y * cy + e2z * cz) * inv_det;
  float v = -(e1x * cx + e1y * cy + e1z * cz) * inv_det;
  float t = (sx * nx + sy * ny + sz * nz) * inv_det;
  *t_out = t;
  *u_out = u;
  *v_out = v;
  return det != 0.0f && u >= 0.0f && v >= 0.0f && u + v <= 1.0f;
}

GR_FN int gr_intersect_mt(float ox, float oy, float oz, float dx, float dy, float dz, float v0x,
                          float v0y, float v0z, float e1x, float e1y, float e1z, float e2x,
                          float e2y, float e2z, float* t_out, float* u_out, float* v_out) {
  float nx, ny, nz;
  gr_triangle_normal(e1x, e1y, e1z, e2x, e2y, e2z, &nx, &ny, &nz);
  return gr_intersect_mt_normal(ox, oy, oz, dx, dy, dz, v0x, v0y, v0z, e1x, e1y, e1z, e2x, e2y, e2z,
                                nx, ny, nz, t_out, u_out, v_out);
}

#endif
