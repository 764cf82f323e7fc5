/* The list path's PE kernel with one work-item per (ray, PE) pair: gridrt_lists.cl's work
 * laid out for a GPU, whose work-items are its SIMD lanes (a packet kernel's float16 would
 * run its 16 rays one after another in each of 4 work-items a group). A work-group runs one
 * task (GrPeTask) with GR_PE_LOCAL_SIZE packets of GR_PACKET_LANES work-items each; work-item
 * k of a packet reads lane k of the packet's pair planes and writes lane k's results: the
 * result planes where it hits, the RAY plane where it hits or is skipped, and its bits of the
 * packet's masks (gathered in local memory; the packet's first work-item stores them). The
 * host reads only the lanes the masks name, so it reads both kernels' results alike, and the
 * hits are the same (pe_closest_lane.h). */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "pe_closest_lane.h"

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE * GR_PACKET_LANES, 1, 1))) void
gridrt_lists_lanes(__global const GrPeTask* tasks, __global const float* pairs,
                   __global const int* pe_tri_begin, __global const GrTriangle* pe_tris,
                   __global float* results, int lanes_total, __global int* first_hit_key,
                   int any_hit, int interrupt, __global const float* seg_planes, int seg_stride) {
  __local int packet_masks[GR_PE_LOCAL_SIZE * GR_LANE_MASK_FIELDS];
  const GrPeTask task = tasks[get_group_id(0)];
  const int item = get_local_id(0);
  const int packet_in_task = item / GR_PACKET_LANES, lane = item % GR_PACKET_LANES;
  __local int* my_masks = packet_masks + packet_in_task * GR_LANE_MASK_FIELDS;
  if (lane < GR_LANE_MASK_FIELDS) my_masks[lane] = 0;
  barrier(CLK_LOCAL_MEM_FENCE);

  const int first = packet_in_task * GR_PACKET_LANES;
  const int packet_exists = first < task.pair_count;
  const int packet_index = task.first_packet + packet_in_task;
  __global const float* packet = pairs + (size_t)packet_index * (GR_PAIR_PLANES * GR_PACKET_LANES);
  int ray_bits = 0, skipped = 0;
  GrLaneHit best;
  best.prim = -1;
  if (packet_exists) {
    ray_bits = as_int(packet[gr_pair_value(GR_PAIR_RAY, lane)]);
    const int pierced = first + lane < task.pair_count;
    int tests = 0;
    if (pierced) {
      /* The pair's interval as gridrt_lists reads it. */
      const float lo = packet[gr_pair_value(GR_PAIR_T_LO, lane)];
      const float hi = packet[gr_pair_value(GR_PAIR_T_HI, lane)];
      const float tmin = (ray_bits & GR_PAIR_LO_OPEN) != 0 ? lo : -INFINITY;
      const float tmax = (ray_bits & GR_PAIR_HI_OPEN) != 0 ? hi : INFINITY;
      const int ray = ray_bits & GR_PAIR_RAY_INDEX;
      if (interrupt) skipped = first_hit_key[ray] < as_int(lo);
      if (!skipped) {
        best = gr_pe_closest_lane(
            packet[gr_pair_value(GR_PAIR_OX, lane)], packet[gr_pair_value(GR_PAIR_OY, lane)],
            packet[gr_pair_value(GR_PAIR_OZ, lane)], packet[gr_pair_value(GR_PAIR_DX, lane)],
            packet[gr_pair_value(GR_PAIR_DY, lane)], packet[gr_pair_value(GR_PAIR_DZ, lane)],
            pe_tris, pe_tri_begin[task.pe], pe_tri_begin[task.pe + 1], tmin, tmax, lo, hi, any_hit,
            &tests);
        if (interrupt && best.prim >= 0) atomic_min(&first_hit_key[ray], as_int(best.t));
      }
    }
    gr_lane_masks_add(my_masks, lane, pierced, best.prim >= 0, skipped, tests);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (!packet_exists) return;
  const size_t all_lanes = (size_t)lanes_total;
  const int out = packet_index * GR_PACKET_LANES + lane;
  const int hit = best.prim >= 0;
  if (hit) gr_lane_store_hit(results, all_lanes, out, &best);
  if (hit || skipped)
    ((__global int*)(results + GR_RESULT_RAY * all_lanes))[out] = ray_bits & GR_PAIR_RAY_INDEX;
  if (lane == 0)
    ((__global GrPacketMasks*)(results + GR_LIST_RESULT_PLANES * all_lanes))[packet_index] =
        gr_lane_masks_read(my_masks);
}
