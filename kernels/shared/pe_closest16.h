/* Phase 1 of GridRT for 16 rays in one PE, shared by both PE kernels: each active lane
 * keeps its closest hit among the PE's triangles [begin, end) that lies in (tmin, tmax)
 * and INSIDE the voxel (t_enter <= t <= t_exit). On equal t the earlier triangle (lower
 * global index: a PE's triangles are in global order) stays. With any_hit the loop stops
 * once every active lane has a hit. best_prim is -1 where a lane found none.
 * With cull, triangle i is skipped when its box (cull_planes, CullPlaneCache) misses
 * packet_box (amin, amax, bmin, bmax of the active lanes on the tangent plane;
 * host/packet_culling.h): the boxes are grown by the test's rounding, so no triangle a
 * lane could hit is skipped. */
#ifndef GRIDRT_PE_CLOSEST16_H
#define GRIDRT_PE_CLOSEST16_H
#include "gridrt_types.h"
#include "ray_triangle16.h"

/* The lanes of a mask (-1 per lane) as 16 bits, lane k in bit k. OpenCL C 1.2 has no
 * horizontal reduction: the disjoint bits are folded by halves. */
inline int gr_lane_bits16(int16 mask) {
  int16 b = mask & ((int16)1 << (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
  int8 b8 = b.lo | b.hi;
  int4 b4 = b8.lo | b8.hi;
  int2 b2 = b4.lo | b4.hi;
  return b2.x | b2.y;
}

inline __attribute__((always_inline)) void gr_pe_closest16(
    const GrRays16* r, __global const GrTriangle* tris, int begin, int end, float16 tmin,
    float16 tmax, float16 t_enter, float16 t_exit, int16 active, int any_hit,
    float16* best_t_out, float16* best_u_out, float16* best_v_out, int16* best_prim_out,
    __global const float* cull_planes, int cull_stride, float4 packet_box, int cull) {
  float16 best_t = tmax, best_u = 0.0f, best_v = 0.0f;
  int16 best_prim = -1;
  /* Triangles go in chunks of 16: first a mask of the ones to test, from 16 boxes at
   * once (a culling branch per triangle would be a mispredicted branch about as dear as
   * the test it saves), then the set bits in increasing order (the tie rule). */
  for (int chunk = begin; chunk < end; chunk += 16) {
    const int n = min(16, end - chunk);
    uint todo = (1u << n) - 1u;
    if (cull) {
      /* Box planes (amin, amax, bmin, bmax), each cull_stride long and padded by 16. */
      const float16 amin = vload16(0, cull_planes + chunk);
      const float16 amax = vload16(0, cull_planes + cull_stride + chunk);
      const float16 bmin = vload16(0, cull_planes + 2 * cull_stride + chunk);
      const float16 bmax = vload16(0, cull_planes + 3 * cull_stride + chunk);
      const int16 miss = (amax < packet_box.s0) | (amin > packet_box.s1) |
                         (bmax < packet_box.s2) | (bmin > packet_box.s3);
      todo &= ~(uint)gr_lane_bits16(miss);
    }
    while (todo) {
      const int i = chunk + 31 - clz(todo & (0u - todo));
      todo &= todo - 1u;
      GrTriangle tri = tris[i];
      float16 t, u, v;
      int16 hit = gr_intersect16(r, tri.v0x, tri.v0y, tri.v0z, tri.e1x, tri.e1y, tri.e1z,
                                 tri.e2x, tri.e2y, tri.e2z, &t, &u, &v);
      /* The in-voxel rule: without it a triangle spanning voxels could win in a PE that
       * comes before the voxel where its hit really lies. */
      hit &= active & (t > tmin) & (t < best_t) & (t >= t_enter) & (t <= t_exit);
      best_t = select(best_t, t, hit);
      best_u = select(best_u, u, hit);
      best_v = select(best_v, v, hit);
      best_prim = select(best_prim, (int16)tri.prim, hit);
      if (any_hit && all((best_prim >= 0) | (active == 0))) {
        chunk = end; /* done: leave both loops */
        break;
      }
    }
  }
  *best_t_out = best_t;
  *best_u_out = best_u;
  *best_v_out = best_v;
  *best_prim_out = best_prim;
}

#endif
