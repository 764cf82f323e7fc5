/* Ray/triangle test of Moeller & Trumbore (1997), "Fast, Minimum Storage Ray/Triangle
 * Intersection". Shared by the host and every kernel so all intersectors round alike.
 * No epsilon: det == 0 (ray in the triangle's plane) is rejected exactly, and a tiny det
 * that overflows 1/det yields inf/NaN barycentrics that fail the comparisons below.
 * The caller checks t against its own (tmin, best) interval; iterating triangles in
 * increasing global index with a strict '<' gives the tie rule (lowest index on equal t). */
#ifndef GRIDRT_MOLLER_TRUMBORE_H
#define GRIDRT_MOLLER_TRUMBORE_H
#include "gridrt_types.h"

GR_FN int gr_intersect_mt(float ox, float oy, float oz, float dx, float dy, float dz, float v0x,
                          float v0y, float v0z, float e1x, float e1y, float e1z, float e2x,
                          float e2y, float e2z, float* t_out, float* u_out, float* v_out) {
  float px = dy * e2z - dz * e2y;
  float py = dz * e2x - dx * e2z;
  float pz = dx * e2y - dy * e2x;
  float det = e1x * px + e1y * py + e1z * pz;
  float inv_det = 1.0f / det;
  float sx = ox - v0x;
  float sy = oy - v0y;
  float sz = oz - v0z;
  float u = (sx * px + sy * py + sz * pz) * inv_det;
  float qx = sy * e1z - sz * e1y;
  float qy = sz * e1x - sx * e1z;
  float qz = sx * e1y - sy * e1x;
  float v = (dx * qx + dy * qy + dz * qz) * inv_det;
  float t = (e2x * qx + e2y * qy + e2z * qz) * inv_det;
  *t_out = t;
  *u_out = u;
  *v_out = v;
  return det != 0.0f && u >= 0.0f && v >= 0.0f && u + v <= 1.0f;
}

#endif
