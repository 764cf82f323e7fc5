/* Brute force: every ray against every triangle. The reference the grid intersectors
 * must match. One work-item tests 16 rays (float16 lanes, PoCL vectorises explicit
 * vector types but not loops across work-items: docs/development.md). */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "ray_triangle16.h"

#if GR_PACKET_LANES != 16
#error "the float16 lanes of this kernel are GR_PACKET_LANES"
#endif

__kernel void brute_intersect(__global const GrRay* rays, int ray_count,
                              __global const GrTriangle* tris, int tri_count, int any_hit,
                              __global GrHit* hits) {
  int first = get_global_id(0) * GR_PACKET_LANES;
  if (first >= ray_count) return;
  float a_ox[GR_PACKET_LANES], a_oy[GR_PACKET_LANES], a_oz[GR_PACKET_LANES], a_dx[GR_PACKET_LANES],
      a_dy[GR_PACKET_LANES], a_dz[GR_PACKET_LANES];
  float a_tmin[GR_PACKET_LANES], a_tmax[GR_PACKET_LANES];
  for (int k = 0; k < GR_PACKET_LANES; ++k) {
    int r = min(first + k, ray_count - 1); /* pad with the last ray */
    GrRay ray = rays[r];
    a_ox[k] = ray.ox;
    a_oy[k] = ray.oy;
    a_oz[k] = ray.oz;
    a_dx[k] = ray.dx;
    a_dy[k] = ray.dy;
    a_dz[k] = ray.dz;
    a_tmin[k] = ray.tmin;
    a_tmax[k] = ray.tmax;
  }
  GrRays16 r16;
  r16.ox = vload16(0, a_ox);
  r16.oy = vload16(0, a_oy);
  r16.oz = vload16(0, a_oz);
  r16.dx = vload16(0, a_dx);
  r16.dy = vload16(0, a_dy);
  r16.dz = vload16(0, a_dz);
  gr_prepare_rays16(&r16);
  float16 tmin = vload16(0, a_tmin);
  float16 best_t = vload16(0, a_tmax);
  float16 best_u = 0.0f, best_v = 0.0f;
  int16 best_prim = -1;
  for (int i = 0; i < tri_count; ++i) {
    GrTriangle tri = tris[i];
    float16 t, u, v;
    int16 hit = gr_intersect16(&r16, &tri, &t, &u, &v);
    hit &= (t > tmin) & (t < best_t);
    best_t = select(best_t, t, hit);
    best_u = select(best_u, u, hit);
    best_v = select(best_v, v, hit);
    best_prim = select(best_prim, (int16)tri.prim, hit);
    if (any_hit && all(best_prim >= 0)) break;
  }
  float o_t[GR_PACKET_LANES], o_u[GR_PACKET_LANES], o_v[GR_PACKET_LANES];
  int o_p[GR_PACKET_LANES];
  vstore16(best_t, 0, o_t);
  vstore16(best_u, 0, o_u);
  vstore16(best_v, 0, o_v);
  vstore16(best_prim, 0, o_p);
  for (int k = 0; k < GR_PACKET_LANES && first + k < ray_count; ++k) {
    GrHit h;
    h.t = o_t[k];
    h.prim = o_p[k];
    h.u = o_u[k];
    h.v = o_v[k];
    hits[first + k] = h;
  }
}
