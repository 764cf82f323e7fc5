/* GridRT processing elements over ray bundles (host/gridrt/bundles/ray_bundles.h): one work-group
 * runs one task of one PE (a non-empty voxel). The task's rays are consecutive in bundle order and
 * stored as planes, so a work-item loads 16 of them with one vload16 per plane and tests them in
 * float16 lanes against the voxel's triangles.
 *
 * The work-item decides itself which lanes pierce the voxel: the slab test with the
 * 3D-DDA's plane distances ((min + k * cell - o) * (1/d), the planes from the host's
 * UniformGrid::pe_box), so two voxels that share a plane share its distance bit for bit
 * and every point of a ray inside the grid lies in the [t_enter, t_exit] of some voxel it
 * pierces. Phase 1 of the reduction: each pierced lane keeps its closest hit INSIDE the
 * voxel (t_enter <= t <= t_exit), so the first PE of a ray's traversal list (entry order)
 * holding a hit also holds the smallest t; phase 2 on the host picks it.
 *
 * INTERRUPT emulates the paper's interrupt chain as gridrt_lists.cl does: a lane is skipped
 * when first_hit_key (per bundle ray, the int bits of the smallest t of a hit) is below its
 * own t_enter.
 *
 * GR_PACKET_PROBE (0 unless the build options set it; `bench.py packets`) cuts every
 * packet short to measure its fixed cost by parts: 1 the dispatch and task read only, 2 the
 * ray loads and the masks' store, 3 + the slab test and the interrupt keys, 4 + the
 * packet's culling box and segment; the triangle tests and hit stores are what the full
 * kernel adds. A probe's images are wrong by design. */
#pragma OPENCL FP_CONTRACT OFF
#include "gridrt_types.h"
#include "pe_closest16.h"

#ifndef GR_PACKET_PROBE
#define GR_PACKET_PROBE 0
#endif

#if GR_PACKET_LANES != 16
#error "the float16 lanes of this kernel are GR_PACKET_LANES"
#endif

/* The ray interval inside [lo, hi] on one axis, narrowing [t0, t1]; a zero direction is
 * inside the slab for every t or for none. fmin/fmax: a NaN product never decides. */
inline void gr_slab16(float16 o, float16 d, float16 inv, float lo, float hi, float16* t0,
                      float16* t1) {
  float16 a = (lo - o) * inv, b = (hi - o) * inv;
  int16 zero = d == 0.0f;
  int16 outside = (o < lo) | (o > hi);
  *t0 = select(fmax(*t0, fmin(a, b)), select(*t0, (float16)INFINITY, outside), zero);
  *t1 = select(fmin(*t1, fmax(a, b)), *t1, zero);
}

/* One packet: 16 consecutive rays of a task against the PE's voxel and triangles, writing
 * its masks and, where a lane hits, its closest in-voxel hit. Always inlined, so that for
 * camera rays (origin and interval splats of one ray) the compiler folds every operation
 * on the common origin into one scalar operation per triangle: the same operations on the
 * same values, so every lane rounds exactly as before. */
inline __attribute__((always_inline)) void gr_bundle_packet(const GrRays16* r, float16 tmin,
                                                            float16 tmax, int16 in_task, int first,
                                                            int out, const GrVoxelBox* box,
                                                            const GrPeGeometry* pe,
                                                            const GrPacketOutput* o,
                                                            GrCullFrame cull, int seg_cull) {
  const int interrupt = o->interrupt;
  /* One result buffer (one map on the host; gridrt_types.h): t, prim, u, v planes of
   * `lanes_total` each, then one GrPacketMasks per packet. */
  __global GrPacketMasks* masks =
      (__global GrPacketMasks*)(o->results + GR_BUNDLE_RESULT_PLANES * (size_t)o->lanes_total);
  /* Padding has a zero direction and never pierces. */
  in_task &= (r->dx != 0.0f) | (r->dy != 0.0f) | (r->dz != 0.0f);

  float16 t_enter = tmin, t_exit = tmax;
  gr_slab16(r->ox, r->dx, 1.0f / r->dx, box->lox, box->hix, &t_enter, &t_exit);
  gr_slab16(r->oy, r->dy, 1.0f / r->dy, box->loy, box->hiy, &t_enter, &t_exit);
  gr_slab16(r->oz, r->dz, 1.0f / r->dz, box->loz, box->hiz, &t_enter, &t_exit);
  int16 pierced = in_task & (t_enter <= t_exit);
#if GR_PACKET_PROBE == 2
  /* The loads and the masks' store only (the slab test's result goes unused). */
  GrPacketMasks loaded = {gr_lane_bits16(in_task), 0, 0, 0};
  masks[out / GR_PACKET_LANES] = loaded;
  return;
#endif
  int16 active = pierced;
  int16 skipped = (int16)0;
  if (interrupt) {
    int16 key = vload16(0, o->first_hit_key + first);
    skipped = pierced & (key < as_int16(t_enter));
    active = pierced & ~skipped;
  }

  GrPacketMasks m;
  m.pierced = 0;
  m.hit = 0;
  m.skipped = 0;
  m.tests = 0;
  if (any(active)) {
    /* The active lanes' box on the culling frame's tangent plane
     * (host/gridrt/culling/packet_culling.h); the host enables culling only when every ray has d.f
     * > 0. */
    float4 packet_box = (float4)0.0f;
    if (cull.enabled != 0.0f) {
      float16 w = r->dx * cull.fx + r->dy * cull.fy + r->dz * cull.fz;
      float16 a = (r->dx * cull.rx + r->dy * cull.ry + r->dz * cull.rz) / w;
      float16 b = (r->dx * cull.ux + r->dy * cull.uy + r->dz * cull.uz) / w;
      packet_box = (float4)(gr_lane_min16(select((float16)INFINITY, a, active)),
                            gr_lane_max16(select((float16)-INFINITY, a, active)),
                            gr_lane_min16(select((float16)INFINITY, b, active)),
                            gr_lane_max16(select((float16)-INFINITY, b, active)));
    }
    GrSegmentPacket seg;
    seg.enabled = 0;
    if (seg_cull) seg = gr_segment_packet16(r, fmax(t_enter, tmin), fmin(t_exit, tmax), active);
#if GR_PACKET_PROBE == 3 || GR_PACKET_PROBE == 4
    /* Stage 3 stops after the slab test and the interrupt keys; stage 4 after the packet's
     * culling box and segment, kept alive through the tests count. */
    if (GR_PACKET_PROBE == 4)
      m.tests = (int)(packet_box.s0 + packet_box.s1 + packet_box.s2 + packet_box.s3) + seg.enabled;
#else
    GrHits16 best;
    gr_pe_closest16(r, pe, tmin, tmax, t_enter, t_exit, active, o->any_hit, packet_box,
                    cull.enabled != 0.0f, &seg, &best, &m.tests);
    m.hit = gr_store_packet_hits(&best, o, out);
    if (interrupt && m.hit) gr_lower_consecutive_keys(&best, o->first_hit_key + first);
#endif
  }
  m.pierced = gr_lane_bits16(pierced);
  m.skipped = gr_lane_bits16(skipped);
  masks[out / GR_PACKET_LANES] = m;
}

__kernel __attribute__((reqd_work_group_size(GR_PE_LOCAL_SIZE, 1, 1))) void gridrt_bundles(
    __global const GrBundleTask* tasks, __global const float* planes, int stride, int common_origin,
    GrRay common, GrGridInfo grid, __global const float* pe_box, __global const int* pe_tri_begin,
    __global const GrTriangle* pe_tris, __global float* results, int lanes,
    __global int* first_hit_key, int any_hit, int interrupt, GrCullFrame cull,
    __global const float* cull_planes, int cull_stride, __global const float* seg_planes,
    int seg_stride, __global const GrCullFrame* set_frames, __global const float* set_planes,
    int set_stride, int sets_enabled) {
  const GrBundleTask task = tasks[get_group_id(0)];
#if GR_PACKET_PROBE == 1
  /* Dispatch only: the task read (kept alive by a store that never happens). */
  if (task.ray_count < 0) results[0] = 1.0f;
  return;
#endif
  /* The PE's box (UniformGrid::pe_box): a uniform grid's voxel as the 3D-DDA's planes
   * (min + k * cell, computed on the host in float) or an adaptive leaf, whose faces are
   * the planes of the grids above it; neighbours share their faces' floats. */
  __global const float* box_planes = pe_box + 6 * task.pe;
  GrVoxelBox box;
  box.lox = box_planes[0];
  box.loy = box_planes[1];
  box.loz = box_planes[2];
  box.hix = box_planes[3];
  box.hiy = box_planes[4];
  box.hiz = box_planes[5];
  GrPeGeometry pe;
  pe.tris = pe_tris;
  pe.begin = pe_tri_begin[task.pe];
  pe.end = pe_tri_begin[task.pe + 1];
  pe.cull_planes = cull_planes;
  pe.cull_stride = cull_stride;
  pe.seg_planes = seg_planes;
  pe.seg_stride = seg_stride;
  GrPacketOutput o;
  o.results = results;
  o.lanes_total = lanes;
  o.first_hit_key = first_hit_key;
  o.any_hit = any_hit;
  o.interrupt = interrupt;
  const int packets = (task.ray_count + GR_PACKET_LANES - 1) / GR_PACKET_LANES;
  /* Packet culling needs a common origin, or a common end: rays towards a light are culled
   * with the boxes seen from the light on their cube face (host/gridrt/culling/light_culling.h;
   * a lane's (a, b) is the same for d and -d). Other rays with their own origins use segment
   * culling. */
  GrCullFrame own_cull = cull;
  own_cull.enabled = 0.0f;
  int own_seg_cull = 1;
  if (sets_enabled && task.cull_set >= 0) {
    own_cull = set_frames[task.cull_set];
    pe.cull_planes = set_planes + (size_t)task.cull_set * 4 * (size_t)set_stride;
    pe.cull_stride = set_stride;
    own_seg_cull = 0;
  }

  /* Each work-item takes a consecutive share of the task's packets: PoCL runs a group's
   * work-items one after another, so every plane is read as one stream (interleaved packets,
   * p += GR_PE_LOCAL_SIZE, made each work-item skip three lines of every four: the warm
   * kernel 8-9 % slower on the default Whitted frame's camera and shadow rays,
   * docs/performance.md). */
  const int per_item = (packets + GR_PE_LOCAL_SIZE - 1) / GR_PE_LOCAL_SIZE;
  const int p_end = min(packets, ((int)get_local_id(0) + 1) * per_item);
  for (int p = get_local_id(0) * per_item; p < p_end; ++p) {
    const int first = task.first_ray + p * GR_PACKET_LANES;
    const int out = task.out_first + p * GR_PACKET_LANES;
    /* Lanes past the task's end read the next rays of the bundle and are masked off. */
    const int16 in_task = GR_LANE_INDEX16 < (int16)(task.ray_count - p * GR_PACKET_LANES);
    GrRays16 r;
    r.dx = vload16(0, planes + GR_PLANE_DX * stride + first);
    r.dy = vload16(0, planes + GR_PLANE_DY * stride + first);
    r.dz = vload16(0, planes + GR_PLANE_DZ * stride + first);
    /* With common_origin (camera rays) only the direction planes are filled: origin and
     * interval come from `common`. */
    if (common_origin) {
      r.ox = common.ox;
      r.oy = common.oy;
      r.oz = common.oz;
      gr_prepare_rays16(&r);
      gr_bundle_packet(&r, (float16)common.tmin, (float16)common.tmax, in_task, first, out, &box,
                       &pe, &o, cull, 0);
    } else {
      r.ox = vload16(0, planes + GR_PLANE_OX * stride + first);
      r.oy = vload16(0, planes + GR_PLANE_OY * stride + first);
      r.oz = vload16(0, planes + GR_PLANE_OZ * stride + first);
      gr_prepare_rays16(&r);
      gr_bundle_packet(&r, vload16(0, planes + GR_PLANE_TMIN * stride + first),
                       vload16(0, planes + GR_PLANE_TMAX * stride + first), in_task, first, out,
                       &box, &pe, &o, own_cull, own_seg_cull);
    }
  }
}
