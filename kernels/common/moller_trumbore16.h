/* Moeller-Trumbore for 16 rays at once (float16 lanes) against one triangle, for the
 * kernels only. Same operations in the same order as gr_intersect_mt (moller_trumbore.h),
 * so with FP_CONTRACT OFF and exact division every lane rounds like the scalar test; the
 * conformance tests check that bit for bit. Returns the lane mask (-1 = hit). */
#ifndef GRIDRT_MOLLER_TRUMBORE16_H
#define GRIDRT_MOLLER_TRUMBORE16_H

typedef struct {
  float16 ox, oy, oz, dx, dy, dz;
#ifdef GR_WATERTIGHT
  /* Each lane's shear (watertight16.h), made once per packet by gr_prepare_rays16. */
  int16 kx, ky, kz;
  float16 sx, sy, sz;
#endif
} GrRays16;

inline int16 gr_intersect_mt16(const GrRays16* r, float v0x, float v0y, float v0z, float e1x,
                               float e1y, float e1z, float e2x, float e2y, float e2z,
                               float16* t_out, float16* u_out, float16* v_out) {
  float16 px = r->dy * e2z - r->dz * e2y;
  float16 py = r->dz * e2x - r->dx * e2z;
  float16 pz = r->dx * e2y - r->dy * e2x;
  float16 det = e1x * px + e1y * py + e1z * pz;
  float16 inv_det = 1.0f / det;
  float16 sx = r->ox - v0x;
  float16 sy = r->oy - v0y;
  float16 sz = r->oz - v0z;
  float16 u = (sx * px + sy * py + sz * pz) * inv_det;
  float16 qx = sy * e1z - sz * e1y;
  float16 qy = sz * e1x - sx * e1z;
  float16 qz = sx * e1y - sy * e1x;
  float16 v = (r->dx * qx + r->dy * qy + r->dz * qz) * inv_det;
  float16 t = (e2x * qx + e2y * qy + e2z * qz) * inv_det;
  *t_out = t;
  *u_out = u;
  *v_out = v;
  return (det != 0.0f) & (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f);
}

#endif
