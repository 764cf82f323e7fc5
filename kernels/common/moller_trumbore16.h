/* Moeller-Trumbore for 16 rays at once (float16 lanes) against one prepared triangle
 * (its normal read, not made), for the kernels only. Same operations in the same order as
 * gr_intersect_mt_normal (moller_trumbore.h), so with FP_CONTRACT OFF and exact division
 * every lane rounds like the scalar test; the conformance tests check that bit for bit.
 * Returns the lane mask (-1 = hit). */
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

inline int16 gr_intersect_mt16(const GrRays16* r, const GrTriangle* tri, float16* t_out,
                               float16* u_out, float16* v_out) {
  const float v0x = tri->v0x, v0y = tri->v0y, v0z = tri->v0z;
  const float e1x = tri->e1x, e1y = tri->e1y, e1z = tri->e1z;
  const float e2x = tri->e2x, e2y = tri->e2y, e2z = tri->e2z;
  const float nx = tri->nx, ny = tri->ny, nz = tri->nz;
  float16 det = -(r->dx * nx + r->dy * ny + r->dz * nz);
  float16 inv_det = 1.0f / det;
  float16 sx = r->ox - v0x;
  float16 sy = r->oy - v0y;
  float16 sz = r->oz - v0z;
  float16 cx = sy * r->dz - sz * r->dy;
  float16 cy = sz * r->dx - sx * r->dz;
  float16 cz = sx * r->dy - sy * r->dx;
  float16 u = (e2x * cx + e2y * cy + e2z * cz) * inv_det;
  float16 v = -(e1x * cx + e1y * cy + e1z * cz) * inv_det;
  float16 t = (sx * nx + sy * ny + sz * nz) * inv_det;
  *t_out = t;
  *u_out = u;
  *v_out = v;
  return (det != 0.0f) & (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f);
}

#endif
