/* GridRT processing elements (Nery et al., Sections III and V): one work-group runs one
 * task of one PE (a non-empty voxel). Its work-items test the task's rays, 16 per
 * work-item in float16 lanes read from one packet of pair planes (GR_PAIR_*), against the
 * voxel's triangles. Phase 1 of the reduction happens here: each (ray, PE) pair keeps
 * only its closest hit that lies INSIDE the voxel (t_enter <= t <= t_exit). A packet's
 * results go to its own lanes of the result planes (GR_RESULT_*), written whole and only
 * when a lane hits, and its masks to its GrPacketMasks: the hits are few among the pairs
 * of secondary rays, and 16 scattered stores per packet, one per pair's slot
 * in the ray-major lists, had cost a noticeable share of the kernel.
 * Phase 2 (per ray, the smallest t over its PEs: the first PE in list order with a hit
 * holds it) runs on the host.
 *
 * INTERRUPT emulates the paper's interrupt chain: a PE skips a ray once a PE earlier in
 * that ray's list has reported a hit before the PE's entry distance (a list is ordered by
 * it); first_hit_key holds the smallest t of a hit, as the int bits of a non-negative
 * float, which order like the floats (atomic_min on ints). */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "pe_closest16.h"

#if GR_PACKET_LANES != 16
#error "the float16 lanes of this kernel are GR_PACKET_LANES"
#endif

/* Plane q of a pair packet (gridrt_types.h). */
inline float16 gr_pair_plane16(__global const float* packet, int q) {
  return vload16(0, packet + gr_pair_value(q, 0));
}

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE, 1, 1))) void gridrt_lists(
    __global const GrPeTask* tasks, __global const float* pairs, __global const int* pe_tri_begin,
    __global const GrTriangle* pe_tris, __global float* results, int lanes_total,
    __global int* first_hit_key, int any_hit, int interrupt, __global const float* seg_planes,
    int seg_stride) {
  GrPeTask task = tasks[get_group_id(0)];
  int first = get_local_id(0) * GR_PACKET_LANES;
  if (first >= task.pair_count) return;
  int lanes = min(GR_PACKET_LANES, task.pair_count - first);
  const int packet_index = task.first_packet + get_local_id(0);
  __global const float* packet = pairs + (size_t)packet_index * (GR_PAIR_PLANES * GR_PACKET_LANES);
  GrRays16 r16;
  r16.ox = gr_pair_plane16(packet, GR_PAIR_OX);
  r16.oy = gr_pair_plane16(packet, GR_PAIR_OY);
  r16.oz = gr_pair_plane16(packet, GR_PAIR_OZ);
  r16.dx = gr_pair_plane16(packet, GR_PAIR_DX);
  r16.dy = gr_pair_plane16(packet, GR_PAIR_DY);
  r16.dz = gr_pair_plane16(packet, GR_PAIR_DZ);
  gr_prepare_rays16(&r16);
  /* The pair's interval (gr_pair_bounds) as the phase-1 loop's four bounds: an open end
   * is the ray's own (t > tmin, t < tmax), a closed one the voxel's (t >= t_enter,
   * t <= t_exit); the other bound of each side lets everything through. */
  const float16 lo = gr_pair_plane16(packet, GR_PAIR_T_LO);
  const float16 hi = gr_pair_plane16(packet, GR_PAIR_T_HI);
  const int16 ray_bits = as_int16(gr_pair_plane16(packet, GR_PAIR_RAY));
  const int16 ray16 = ray_bits & GR_PAIR_RAY_INDEX;
  const float16 tmin = select((float16)(-INFINITY), lo, (ray_bits & GR_PAIR_LO_OPEN) != 0);
  const float16 tmax = select((float16)INFINITY, hi, (ray_bits & GR_PAIR_HI_OPEN) != 0);
  const float16 t_enter = lo, t_exit = hi;
  int ray_of[GR_PACKET_LANES];
  vstore16(ray16, 0, ray_of);
  const int16 pierced = GR_LANE_INDEX16 < (int16)lanes;
  int16 active = pierced, skipped = (int16)0;
  if (interrupt) {
    int key[GR_PACKET_LANES];
    for (int k = 0; k < GR_PACKET_LANES; ++k)
      key[k] = k < lanes ? first_hit_key[ray_of[k]] : INT_MAX;
    skipped = pierced & (vload16(0, key) < as_int16(t_enter));
    active = pierced & ~skipped;
  }
  const size_t all_lanes = (size_t)lanes_total;
  __global int* out_ray = (__global int*)(results + GR_RESULT_RAY * all_lanes);
  __global GrPacketMasks* masks =
      (__global GrPacketMasks*)(results + GR_LIST_RESULT_PLANES * all_lanes);
  const int out = packet_index * GR_PACKET_LANES;
  GrPacketMasks m;
  m.pierced = gr_lane_bits16(pierced);
  m.hit = 0;
  m.skipped = gr_lane_bits16(skipped);
  m.tests = 0;
  if (any(active)) {
    /* The list path's rays have their own origins: segment culling. */
    const GrSegmentPacket seg = gr_segment_packet16(&r16, lo, hi, active);
    GrPeGeometry pe;
    pe.tris = pe_tris;
    pe.begin = pe_tri_begin[task.pe];
    pe.end = pe_tri_begin[task.pe + 1];
    pe.cull_planes = (__global const float*)0; /* no packet culling on this path */
    pe.cull_stride = 0;
    pe.seg_planes = seg_planes;
    pe.seg_stride = seg_stride;
    GrPacketOutput o;
    o.results = results;
    o.lanes_total = lanes_total;
    o.first_hit_key = first_hit_key;
    o.any_hit = any_hit;
    o.interrupt = interrupt;
    GrHits16 best;
    gr_pe_closest16(&r16, &pe, tmin, tmax, t_enter, t_exit, active, any_hit, (float4)0.0f, 0, &seg,
                    &best, &m.tests);
    m.hit = gr_store_packet_hits(&best, &o, out);
    if (interrupt && m.hit) gr_lower_gathered_keys(&best, m.hit, first_hit_key, ray16);
  }
  if (m.hit | m.skipped) vstore16(ray16, 0, out_ray + out);
  masks[packet_index] = m;
}
