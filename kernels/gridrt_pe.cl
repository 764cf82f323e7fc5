/* GridRT processing elements (Nery et al., Sections III and V): one work-group runs one
 * task of one PE (a non-empty voxel). Its work-items test the task's rays, 16 per
 * work-item in float16 lanes, against the voxel's triangles. Phase 1 of the reduction
 * happens here: each (ray, PE) pair keeps only its closest hit that lies INSIDE the voxel
 * (t_enter <= t <= t_exit), written to the pair's slot of the ray's traversal list.
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

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE, 1, 1)))
void gridrt_pe(__global const GrPeTask* tasks, __global const GrPeEntry* entries,
               __global const GrRay* rays, __global const int* pe_tri_begin,
               __global const GrTriangle* pe_tris, __global GrHit* slot_hits,
               __global int* first_hit_key, int any_hit, int interrupt,
               __global const float* seg_planes, int seg_stride) {
  GrPeTask task = tasks[get_group_id(0)];
  int first = get_local_id(0) * LANES;
  if (first >= task.entry_count) return;
  int lanes = min(LANES, task.entry_count - first);
  float a_ox[LANES], a_oy[LANES], a_oz[LANES], a_dx[LANES], a_dy[LANES], a_dz[LANES];
  float a_lo[LANES], a_hi[LANES], a_t0[LANES], a_t1[LANES];
  int a_active[LANES], a_slot[LANES], a_ray[LANES], a_key[LANES];
  int live = 0;
  for (int k = 0; k < LANES; ++k) {
    GrPeEntry e = entries[task.first_entry + first + min(k, lanes - 1)];
    GrRay ray = rays[e.ray];
    a_ox[k] = ray.ox; a_oy[k] = ray.oy; a_oz[k] = ray.oz;
    a_dx[k] = ray.dx; a_dy[k] = ray.dy; a_dz[k] = ray.dz;
    a_lo[k] = ray.tmin; a_hi[k] = ray.tmax;
    a_t0[k] = e.t_enter; a_t1[k] = e.t_exit;
    a_slot[k] = task.slot_base + e.slot; a_ray[k] = e.ray; a_key[k] = as_int(e.t_enter);
    int active = k < lanes;
    if (interrupt && active && first_hit_key[e.ray] < as_int(e.t_enter)) {
      active = 0;
      GrHit skipped;
      skipped.t = 0.0f; skipped.prim = GR_SKIPPED; skipped.u = 0.0f; skipped.v = 0.0f;
      slot_hits[a_slot[k]] = skipped;
    }
    a_active[k] = active ? -1 : 0;
    live |= active;
  }
  if (!live) return;
  GrRays16 r16;
  r16.ox = vload16(0, a_ox); r16.oy = vload16(0, a_oy); r16.oz = vload16(0, a_oz);
  r16.dx = vload16(0, a_dx); r16.dy = vload16(0, a_dy); r16.dz = vload16(0, a_dz);
  float16 tmin = vload16(0, a_lo);
  float16 tmax = vload16(0, a_hi);
  float16 t_enter = vload16(0, a_t0);
  float16 t_exit = vload16(0, a_t1);
  int16 active = vload16(0, a_active);
  /* The list path's rays have their own origins: segment culling. */
  const GrSegmentPacket seg =
      gr_segment_packet16(&r16, fmax(t_enter, tmin), fmin(t_exit, tmax), active);
  float16 best_t, best_u, best_v;
  int16 best_prim;
  gr_pe_closest16(&r16, pe_tris, pe_tri_begin[task.pe], pe_tri_begin[task.pe + 1], tmin, tmax,
                  t_enter, t_exit, active, any_hit, &best_t, &best_u, &best_v, &best_prim,
                  (__global const float*)0, 0, (float4)0.0f, 0, &seg, seg_planes, seg_stride);
  float o_t[LANES], o_u[LANES], o_v[LANES];
  int o_p[LANES];
  vstore16(best_t, 0, o_t); vstore16(best_u, 0, o_u); vstore16(best_v, 0, o_v);
  vstore16(best_prim, 0, o_p);
  for (int k = 0; k < lanes; ++k) {
    if (!a_active[k]) continue;
    GrHit h;
    h.t = o_t[k]; h.prim = o_p[k]; h.u = o_u[k]; h.v = o_v[k];
    slot_hits[a_slot[k]] = h;
    if (interrupt && h.prim >= 0) atomic_min(&first_hit_key[a_ray[k]], a_key[k]);
  }
}
