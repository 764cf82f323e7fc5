/* Phase 1 of GridRT for one ray in one PE, for the lane kernels (one work-item per ray,
 * kernels/gridrt_lists_lanes.cl and gridrt_bundles_lanes.cl; a GPU's layout): the ray keeps
 * its closest hit among the PE's triangles [begin, end) that lies in (tmin, tmax) and INSIDE
 * the voxel (t_enter <= t <= t_exit), the earlier triangle on equal t. The same test, in the
 * same triangle order, as gr_pe_closest16 (pe_closest16.h) runs in each lane, so each ray
 * finds the same closest hit; with any_hit it stops at its first hit (the packet kernel
 * stops once all 16 lanes have one: either is "some hit"). No culling: culling only skips
 * triangles a ray cannot hit, and its packet-wide boxes would need the 16 work-items to
 * agree first. Also the lane kernels' helpers for their packets' masks. */
#ifndef GRIDRT_PE_CLOSEST_LANE_H
#define GRIDRT_PE_CLOSEST_LANE_H
#include "gridrt_types.h"
#include "ray_triangle.h"

/* The closest in-voxel hit of one ray (prim -1: none). */
typedef struct {
  float t, u, v;
  int prim;
} GrLaneHit;

/* The kernels' test of one ray against one prepared triangle: Moeller-Trumbore with the
 * stored normal (as gr_intersect_mt16), or the watertight test on the stored layout. */
inline int gr_intersect_lane(float ox, float oy, float oz, float dx, float dy, float dz,
                             const GrTriangle* tri, float* t, float* u, float* v) {
#ifdef GR_WATERTIGHT
  return gr_intersect_watertight(ox, oy, oz, dx, dy, dz, tri->v0x, tri->v0y, tri->v0z, tri->e1x,
                                 tri->e1y, tri->e1z, tri->e2x, tri->e2y, tri->e2z, t, u, v);
#else
  return gr_intersect_mt_normal(ox, oy, oz, dx, dy, dz, tri->v0x, tri->v0y, tri->v0z, tri->e1x,
                                tri->e1y, tri->e1z, tri->e2x, tri->e2y, tri->e2z, tri->nx, tri->ny,
                                tri->nz, t, u, v);
#endif
}

/* tests_out: the ray-triangle tests run. */
inline GrLaneHit gr_pe_closest_lane(float ox, float oy, float oz, float dx, float dy, float dz,
                                    __global const GrTriangle* tris, int begin, int end, float tmin,
                                    float tmax, float t_enter, float t_exit, int any_hit,
                                    int* tests_out) {
  GrLaneHit best;
  best.t = tmax;
  best.u = 0.0f;
  best.v = 0.0f;
  best.prim = -1;
  int tested = 0;
  for (int i = begin; i < end; ++i) {
    const GrTriangle tri = tris[i];
    ++tested;
    float t, u, v;
    /* The in-voxel rule as in gr_pe_closest16. */
    if (gr_intersect_lane(ox, oy, oz, dx, dy, dz, &tri, &t, &u, &v) && t > tmin && t < best.t &&
        t >= t_enter && t <= t_exit) {
      best.t = t;
      best.u = u;
      best.v = v;
      best.prim = tri.prim;
      if (any_hit) break;
    }
  }
  *tests_out = tested;
  return best;
}

/* A lane's hit into its lane `out` of the result planes (GR_RESULT_*, each lanes_total long),
 * as gr_store_packet_hits writes a packet's. */
inline void gr_lane_store_hit(__global float* results, size_t lanes_total, int out,
                              const GrLaneHit* hit) {
  results[GR_RESULT_T * lanes_total + out] = hit->t;
  ((__global int*)(results + GR_RESULT_PRIM * lanes_total))[out] = hit->prim;
  results[GR_RESULT_U * lanes_total + out] = hit->u;
  results[GR_RESULT_V * lanes_total + out] = hit->v;
}

/* A work-group's packets' masks in local memory, GR_LANE_MASK_FIELDS ints a packet
 * (GrPacketMasks' fields in order), gathered from the packet's 16 work-items with local
 * atomics: each sets its own lane's bits and adds its tests. */
#define GR_LANE_MASK_FIELDS 4
inline void gr_lane_masks_add(__local int* packet_masks, int lane, int pierced, int hit,
                              int skipped, int tests) {
  const int bit = 1 << lane;
  if (pierced) atomic_or(&packet_masks[0], bit);
  if (hit) atomic_or(&packet_masks[1], bit);
  if (skipped) atomic_or(&packet_masks[2], bit);
  if (tests) atomic_add(&packet_masks[3], tests);
}

inline GrPacketMasks gr_lane_masks_read(__local const int* packet_masks) {
  GrPacketMasks m;
  m.pierced = packet_masks[0];
  m.hit = packet_masks[1];
  m.skipped = packet_masks[2];
  m.tests = packet_masks[3];
  return m;
}

#endif
