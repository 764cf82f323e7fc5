/* GridRT processing elements (Nery et al., Sections III and V): one work-group runs one
 * task of one PE (a non-empty voxel). Its work-items test the task's rays, 16 per
 * work-item in float16 lanes read from one packet of pair planes (GR_PAIR_*), against the
 * voxel's triangles. Phase 1 of the reduction happens here: each (ray, PE) pair keeps
 * only its closest hit that lies INSIDE the voxel (t_enter <= t <= t_exit), written to
 * the pair's slot of the ray's traversal list.
 * Phase 2 (first PE in list order with a hit wins) runs on the host.
 *
 * INTERRUPT emulates the paper's interrupt chain: a PE skips a ray once a PE earlier in
 * that ray's list has reported a hit. "Earlier" is a smaller entry distance (a list is
 * ordered by it); first_hit_key holds the smallest t_enter of a PE with a hit, as the
 * int bits of a non-negative float, which order like the floats (atomic_min on ints). */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "pe_closest16.h"

#define LANES 16
#define GR_SKIPPED (-2) /* prim of a slot whose test was skipped by the interrupt */

/* Plane q of a pair packet (gridrt_types.h). */
inline float16 gr_pair_plane16(__global const float* packet, int q) {
  return vload16(0, packet + gr_pair_value(q, 0));
}

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE, 1, 1)))
void gridrt_pe(__global const GrPeTask* tasks, __global const float* pairs,
               __global const int* pe_tri_begin, __global const GrTriangle* pe_tris,
               __global GrHit* slot_hits, __global int* first_hit_key, int any_hit,
               int interrupt, __global const float* seg_planes, int seg_stride) {
  GrPeTask task = tasks[get_group_id(0)];
  int first = get_local_id(0) * LANES;
  if (first >= task.pair_count) return;
  int lanes = min(LANES, task.pair_count - first);
  __global const float* packet =
      pairs + (size_t)(task.first_packet + get_local_id(0)) * (GR_PAIR_PLANES * LANES);
  GrRays16 r16;
  r16.ox = gr_pair_plane16(packet, GR_PAIR_OX);
  r16.oy = gr_pair_plane16(packet, GR_PAIR_OY);
  r16.oz = gr_pair_plane16(packet, GR_PAIR_OZ);
  r16.dx = gr_pair_plane16(packet, GR_PAIR_DX);
  r16.dy = gr_pair_plane16(packet, GR_PAIR_DY);
  r16.dz = gr_pair_plane16(packet, GR_PAIR_DZ);
  float16 tmin = gr_pair_plane16(packet, GR_PAIR_TMIN);
  float16 tmax = gr_pair_plane16(packet, GR_PAIR_TMAX);
  float16 t_enter = gr_pair_plane16(packet, GR_PAIR_T_ENTER);
  float16 t_exit = gr_pair_plane16(packet, GR_PAIR_T_EXIT);
  int ray_of[LANES], slot_of[LANES];
  vstore16(as_int16(gr_pair_plane16(packet, GR_PAIR_RAY)), 0, ray_of);
  vstore16(as_int16(gr_pair_plane16(packet, GR_PAIR_SLOT)), 0, slot_of);
  const int16 lane_index = (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  int16 active = lane_index < (int16)lanes;
  if (interrupt) {
    int a_active[LANES];
    int live = 0;
    for (int k = 0; k < LANES; ++k) {
      int on = k < lanes;
      if (on && first_hit_key[ray_of[k]] < as_int(packet[gr_pair_value(GR_PAIR_T_ENTER, k)])) {
        on = 0;
        GrHit skipped;
        skipped.t = 0.0f; skipped.prim = GR_SKIPPED; skipped.u = 0.0f; skipped.v = 0.0f;
        slot_hits[task.slot_base + slot_of[k]] = skipped;
      }
      a_active[k] = on ? -1 : 0;
      live |= on;
    }
    if (!live) return;
    active = vload16(0, a_active);
  }
  /* The list path's rays have their own origins: segment culling. */
  const GrSegmentPacket seg =
      gr_segment_packet16(&r16, fmax(t_enter, tmin), fmin(t_exit, tmax), active);
  float16 best_t, best_u, best_v;
  int16 best_prim;
  gr_pe_closest16(&r16, pe_tris, pe_tri_begin[task.pe], pe_tri_begin[task.pe + 1], tmin, tmax,
                  t_enter, t_exit, active, any_hit, &best_t, &best_u, &best_v, &best_prim,
                  (__global const float*)0, 0, (float4)0.0f, 0, &seg, seg_planes, seg_stride);
  float o_t[LANES], o_u[LANES], o_v[LANES];
  int o_p[LANES], o_active[LANES];
  vstore16(best_t, 0, o_t); vstore16(best_u, 0, o_u); vstore16(best_v, 0, o_v);
  vstore16(best_prim, 0, o_p);
  vstore16(active, 0, o_active);
  for (int k = 0; k < lanes; ++k) {
    if (!o_active[k]) continue;
    GrHit h;
    h.t = o_t[k]; h.prim = o_p[k]; h.u = o_u[k]; h.v = o_v[k];
    slot_hits[task.slot_base + slot_of[k]] = h;
    if (interrupt && h.prim >= 0)
      atomic_min(&first_hit_key[ray_of[k]], as_int(packet[gr_pair_value(GR_PAIR_T_ENTER, k)]));
  }
}
