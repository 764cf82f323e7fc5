/* The ray bundles' PE kernel with one work-item per ray: gridrt_bundles.cl's work laid out
 * for a GPU (see gridrt_lists_lanes.cl). A work-group runs one task (GrBundleTask), its
 * packets GR_PE_LOCAL_SIZE at a time, GR_PACKET_LANES work-items a packet: work-item k of a
 * packet takes the packet's ray k, decides like gridrt_bundles whether it pierces the voxel
 * (the same slab test, scalar), tests it (pe_closest_lane.h: no culling) and writes lane k's
 * results and its bits of the packet's masks, which the host reads as gridrt_bundles'. */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "pe_closest_lane.h"

/* gr_slab16 (gridrt_bundles.cl) for one ray. */
inline void gr_slab_lane(float o, float d, float inv, float lo, float hi, float* t0, float* t1) {
  const float a = (lo - o) * inv, b = (hi - o) * inv;
  if (d == 0.0f) {
    if (o < lo || o > hi) *t0 = INFINITY;
  } else {
    *t0 = fmax(*t0, fmin(a, b));
    *t1 = fmin(*t1, fmax(a, b));
  }
}

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE * GR_PACKET_LANES, 1, 1))) void
gridrt_bundles_lanes(__global const GrBundleTask* tasks, __global const float* planes, int stride,
                     int common_origin, GrRay common, GrGridInfo grid, __global const float* pe_box,
                     __global const int* pe_tri_begin, __global const GrTriangle* pe_tris,
                     __global float* results, int lanes, __global int* first_hit_key, int any_hit,
                     int interrupt, GrCullFrame cull, __global const float* cull_planes,
                     int cull_stride, __global const float* seg_planes, int seg_stride,
                     __global const GrCullFrame* set_frames, __global const float* set_planes,
                     int set_stride, int sets_enabled) {
  __local int packet_masks[GR_PE_LOCAL_SIZE * GR_LANE_MASK_FIELDS];
  const GrBundleTask task = tasks[get_group_id(0)];
  __global const float* box = pe_box + 6 * task.pe;
  const int begin = pe_tri_begin[task.pe], end = pe_tri_begin[task.pe + 1];
  const int item = get_local_id(0);
  const int packet_in_step = item / GR_PACKET_LANES, lane = item % GR_PACKET_LANES;
  __local int* my_masks = packet_masks + packet_in_step * GR_LANE_MASK_FIELDS;
  const size_t all_lanes = (size_t)lanes;
  const int packets = (task.ray_count + GR_PACKET_LANES - 1) / GR_PACKET_LANES;
  for (int step = 0; step < packets; step += GR_PE_LOCAL_SIZE) {
    const int p = step + packet_in_step;
    if (lane < GR_LANE_MASK_FIELDS) my_masks[lane] = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    const int ray = task.first_ray + p * GR_PACKET_LANES + lane;
    const int out = task.out_first + p * GR_PACKET_LANES + lane;
    GrLaneHit best;
    best.prim = -1;
    if (p < packets) {
      int pierced = p * GR_PACKET_LANES + lane < task.ray_count;
      float ox = common.ox, oy = common.oy, oz = common.oz, tmin = common.tmin, tmax = common.tmax;
      float dx = 0.0f, dy = 0.0f, dz = 0.0f;
      if (pierced) {
        dx = planes[GR_PLANE_DX * stride + ray];
        dy = planes[GR_PLANE_DY * stride + ray];
        dz = planes[GR_PLANE_DZ * stride + ray];
        if (!common_origin) {
          ox = planes[GR_PLANE_OX * stride + ray];
          oy = planes[GR_PLANE_OY * stride + ray];
          oz = planes[GR_PLANE_OZ * stride + ray];
          tmin = planes[GR_PLANE_TMIN * stride + ray];
          tmax = planes[GR_PLANE_TMAX * stride + ray];
        }
      }
      /* Padding has a zero direction and never pierces. */
      pierced &= dx != 0.0f || dy != 0.0f || dz != 0.0f;
      float t_enter = tmin, t_exit = tmax;
      gr_slab_lane(ox, dx, 1.0f / dx, box[0], box[3], &t_enter, &t_exit);
      gr_slab_lane(oy, dy, 1.0f / dy, box[1], box[4], &t_enter, &t_exit);
      gr_slab_lane(oz, dz, 1.0f / dz, box[2], box[5], &t_enter, &t_exit);
      pierced &= t_enter <= t_exit;
      int skipped = 0, tests = 0;
      if (pierced && interrupt) skipped = first_hit_key[ray] < as_int(t_enter);
      if (pierced && !skipped) {
        best = gr_pe_closest_lane(ox, oy, oz, dx, dy, dz, pe_tris, begin, end, tmin, tmax, t_enter,
                                  t_exit, any_hit, &tests);
        if (best.prim >= 0) {
          gr_lane_store_hit(results, all_lanes, out, &best);
          if (interrupt) atomic_min(&first_hit_key[ray], as_int(best.t));
        }
      }
      gr_lane_masks_add(my_masks, lane, pierced, best.prim >= 0, skipped, tests);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (p < packets && lane == 0)
      ((__global GrPacketMasks*)(results +
                                 GR_BUNDLE_RESULT_PLANES * all_lanes))[out / GR_PACKET_LANES] =
          gr_lane_masks_read(my_masks);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}
