/* Phase 1 of GridRT for 16 rays in one PE, shared by both PE kernels: each active lane
 * keeps its closest hit among the PE's triangles [begin, end) that lies in (tmin, tmax)
 * and INSIDE the voxel (t_enter <= t <= t_exit). On equal t the earlier triangle (lower
 * global index: a PE's triangles are in global order) stays. With any_hit the loop stops
 * once every active lane has a hit. best_prim is -1 where a lane found none. */
#ifndef GRIDRT_PE_CLOSEST16_H
#define GRIDRT_PE_CLOSEST16_H
#include "gridrt_types.h"
#include "ray_triangle16.h"

inline __attribute__((always_inline)) void gr_pe_closest16(const GrRays16* r, __global const GrTriangle* tris, int begin,
                            int end, float16 tmin, float16 tmax, float16 t_enter,
                            float16 t_exit, int16 active, int any_hit, float16* best_t_out,
                            float16* best_u_out, float16* best_v_out, int16* best_prim_out) {
  float16 best_t = tmax, best_u = 0.0f, best_v = 0.0f;
  int16 best_prim = -1;
  for (int i = begin; i < end; ++i) {
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
    if (any_hit && all((best_prim >= 0) | (active == 0))) break;
  }
  *best_t_out = best_t;
  *best_u_out = best_u;
  *best_v_out = best_v;
  *best_prim_out = best_prim;
}

#endif
