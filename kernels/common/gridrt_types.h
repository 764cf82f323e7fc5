/* Struct layouts shared by the host (C++) and the kernels (OpenCL C 1.2).
 * One truth: both include this file; the host pins every size with static_assert (end of
 * file). No float3 (16 bytes in OpenCL C): scalars only. */
#ifndef GRIDRT_TYPES_H
#define GRIDRT_TYPES_H

#ifdef __OPENCL_C_VERSION__
#define GR_FN static inline
#else
#define GR_FN static inline
#endif

/* A ray: origin, direction (unit length), and the open interval (tmin, tmax) searched. */
typedef struct {
  float ox, oy, oz, tmin;
  float dx, dy, dz, tmax;
} GrRay; /* 32 bytes */

/* A triangle prepared for the intersectors: first vertex, the two edges from it and
 * their cross product n = e1 x e2 (gr_triangle_normal: Moeller-Trumbore). In the
 * watertight build the e fields hold the vertices v1 and v2 themselves (v0 + e1 in float
 * does not always give back v1, and neighbours must share their edge vertices bit for bit
 * to be watertight) and n is zero, unused. */
typedef struct {
  float v0x, v0y, v0z;
  float e1x, e1y, e1z;
  float e2x, e2y, e2z;
  int prim;          /* global triangle index in load order */
  int vertex_layout; /* 1: e1/e2 hold v1/v2 (watertight build), 0: edges */
  int pad1;
  float nx, ny, nz;
  int pad2;
} GrTriangle; /* 64 bytes */

/* The closest hit found for one ray (or one ray inside one PE): prim < 0 means none. */
typedef struct {
  float t;
  int prim;
  float u, v; /* barycentrics of vertices 1 and 2 */
} GrHit;      /* 16 bytes */

/* The uniform grid as the kernels see it. */
typedef struct {
  float minx, miny, minz, pad0;
  float cellx, celly, cellz, pad1; /* voxel size per axis */
  int nx, ny, nz, pe_count;
} GrGridInfo; /* 48 bytes */

/* Rays per packet, on both sides: a work-item of every kernel tests one packet in float16
 * lanes (the kernels' vector types are 16 wide: brute.cl, gridrt_lists.cl and
 * gridrt_bundles.cl stop on another value), a camera tile is one packet, and the host
 * bins, bundles and reduces the rays by packet. */
#define GR_PACKET_LANES 16

/* The list path's (ray, PE) pairs, binned per PE, GR_PACKET_LANES to a packet,
 * each carrying its ray, so a work-item loads its packet, one vload16 per plane, instead
 * of gathering rays: plane q of lane k at gr_pair_value(q, k) (structure of arrays).
 * A pair's hits lie between T_LO and T_HI: the ray's interval (tmin, tmax) and the PE's
 * [t_enter, t_exit] along it (the in-voxel rule) in one interval, each end either the
 * ray's own (open) or the voxel's (closed), as bits of RAY (gr_pair_bounds). RAY holds int
 * bits: the ray's index in the batch (below GR_PAIR_MAX_RAYS) and those two bits. Lanes
 * past a part's last pair are zero. */
#define GR_PAIR_OX 0
#define GR_PAIR_OY 1
#define GR_PAIR_OZ 2
#define GR_PAIR_DX 3
#define GR_PAIR_DY 4
#define GR_PAIR_DZ 5
#define GR_PAIR_T_LO 6 /* the smallest t a hit may have: max(tmin, t_enter) */
#define GR_PAIR_T_HI 7 /* the largest: min(tmax, t_exit) */
#define GR_PAIR_RAY 8
#define GR_PAIR_PLANES 9
#define GR_PAIR_MAX_RAYS (1 << 29)
#define GR_PAIR_RAY_INDEX (GR_PAIR_MAX_RAYS - 1)
#define GR_PAIR_LO_OPEN (1 << 29) /* T_LO is the ray's tmin: a hit lies strictly above it */
#define GR_PAIR_HI_OPEN (1 << 30) /* T_HI is the ray's tmax: a hit lies strictly below it */
#define gr_pair_value(q, k) ((q)*GR_PACKET_LANES + (k))

/* The bounds of a pair's hits, t in (tmin, tmax) and in [t_enter, t_exit], as one interval
 * from *lo to *hi whose open ends are GR_PAIR_LO_OPEN / GR_PAIR_HI_OPEN in the returned bits:
 * the same test with two comparisons. Where a comparison of the ends is false both ways (a
 * NaN), the end is NaN and nothing passes, as before. */
GR_FN int gr_pair_bounds(float tmin, float tmax, float t_enter, float t_exit, float* lo,
                         float* hi) {
  int bits = 0;
  if (tmin >= t_enter) {
    *lo = tmin;
    bits |= GR_PAIR_LO_OPEN;
  } else {
    *lo = t_enter > tmin ? t_enter : tmin + t_enter; /* the NaN of either */
  }
  if (tmax <= t_exit) {
    *hi = tmax;
    bits |= GR_PAIR_HI_OPEN;
  } else {
    *hi = t_exit < tmax ? t_exit : tmax + t_exit;
  }
  return bits;
}

/* One work-group's share of one PE: the pair_count pairs from packet first_packet on
 * (work-item w takes packet first_packet + w, and writes that packet's results). */
typedef struct {
  int pe;
  int first_packet;
  int pair_count;
  int pad;
} GrPeTask; /* 16 bytes */

/* Ray bundles (host/gridrt/bundles/ray_bundles.h): rays reordered so that rays close in direction
 * sit next to each other, stored as planes (structure of arrays), tested 16 at a time. A task is
 * one work-group's share of one PE: the bundle-order rays [first_ray, first_ray + ray_count), whose
 * 16-ray packets write their results from lane out_first (a multiple of 16) and their masks from
 * packet out_first / 16. cull_set: for rays towards a light, the cube face (0..5) whose culling
 * frame and boxes (host/gridrt/culling/light_culling.h) serve the task's rays; -1 for none. */
typedef struct {
  int pe;
  int first_ray;
  int ray_count;
  int out_first;
  int cull_set;
} GrBundleTask; /* 20 bytes */

/* Phase 1's results, one buffer a batch, for both kernels: planes of `lanes` values each
 * (packet p's lane k at p * 16 + k), t, prim, u and v (written for the packets with a
 * hit), then for the list kernel RAY (the lane's ray, for packets with a hit or a skip),
 * then one GrPacketMasks per packet. prim and RAY hold int bits. */
#define GR_RESULT_T 0
#define GR_RESULT_PRIM 1
#define GR_RESULT_U 2
#define GR_RESULT_V 3
#define GR_RESULT_RAY 4
#define GR_BUNDLE_RESULT_PLANES 4
#define GR_LIST_RESULT_PLANES 5

/* What one packet of one task did, one bit per lane. */
typedef struct {
  int pierced;   /* the ray pierces the PE's voxel (the pair is in its traversal list) */
  int hit;       /* ... and has a hit inside it (t, prim, u, v written for this lane) */
  int skipped;   /* ... and was skipped by the interrupt (an earlier PE had a hit) */
  int tests;     /* ray-triangle tests the packet ran after culling (triangles x active lanes) */
} GrPacketMasks; /* 16 bytes */

/* Packet culling for rays with a common origin (host/gridrt/culling/packet_culling.h): a direction
 * d is put on the tangent plane of the frame as a = d.r / d.f, b = d.u / d.f; a packet's box over
 * its lanes' (a, b) that misses a triangle's conservative box (read from four planes,
 * CullPlaneCache) skips the triangle. */
typedef struct {
  float fx, fy, fz, enabled; /* forward: every culled ray has d.f > 0; enabled 0: no culling */
  float rx, ry, rz, pad0;
  float ux, uy, uz, pad1;
} GrCullFrame; /* 48 bytes */

/* The planes of a bundle buffer, each `stride` floats long. */
#define GR_PLANE_OX 0
#define GR_PLANE_OY 1
#define GR_PLANE_OZ 2
#define GR_PLANE_DX 3
#define GR_PLANE_DY 4
#define GR_PLANE_DZ 5
#define GR_PLANE_TMIN 6
#define GR_PLANE_TMAX 7
#define GR_PLANES 8

/* Segment culling for rays with their own origins (host/gridrt/culling/segment_culling.h): per PE
 * triangle (pe_triangles order) the planes below, each `stride` floats long: the three
 * vertices as the ray/triangle test sees them, n = e1 x e2, |e1| |e2| (the test's scale;
 * +infinity for a degenerate triangle, never culled) and |v0|_1 + |e1| + |e2| (its reach
 * from the world origin, for the rounding margin). */
#define GR_SEG_V0X 0
#define GR_SEG_V0Y 1
#define GR_SEG_V0Z 2
#define GR_SEG_V1X 3
#define GR_SEG_V1Y 4
#define GR_SEG_V1Z 5
#define GR_SEG_V2X 6
#define GR_SEG_V2Y 7
#define GR_SEG_V2Z 8
#define GR_SEG_NX 9
#define GR_SEG_NY 10
#define GR_SEG_NZ 11
#define GR_SEG_SCALE 12
#define GR_SEG_REACH 13
#define GR_SEG_PLANES 14

/* A voxel's box, [lo, hi] on each axis: the slabs a PE kernel tests its packets against. */
typedef struct {
  float lox, loy, loz;
  float hix, hiy, hiz;
} GrVoxelBox; /* 24 bytes */

#ifdef __OPENCL_C_VERSION__
/* What the phase-1 loop of a PE reads (kernels only: it holds pointers): the PE's
 * triangles tris[begin, end), the packet-culling boxes and the segment-culling planes of
 * every PE triangle (null and 0 where a path has none). */
typedef struct {
  __global const GrTriangle* tris;
  int begin, end;
  __global const float* cull_planes;
  int cull_stride;
  __global const float* seg_planes;
  int seg_stride;
} GrPeGeometry;

/* How a packet is tested and where its phase-1 results go: the result planes of
 * lanes_total lanes (GR_RESULT_*), the interrupt's keys, the hit mode. */
typedef struct {
  __global float* results;
  int lanes_total;
  __global int* first_hit_key;
  int any_hit, interrupt;
} GrPacketOutput;

/* The closest in-voxel hit of each lane of a packet (prim -1: none). */
typedef struct {
  float16 t, u, v;
  int16 prim;
} GrHits16;
#endif

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(GrRay) == 32, "GrRay layout");
static_assert(sizeof(GrTriangle) == 64, "GrTriangle layout");
static_assert(sizeof(GrHit) == 16, "GrHit layout");
static_assert(sizeof(GrGridInfo) == 48, "GrGridInfo layout");
static_assert(sizeof(GrPeTask) == 16, "GrPeTask layout");
static_assert(sizeof(GrBundleTask) == 20, "GrBundleTask layout");
static_assert(sizeof(GrPacketMasks) == 16, "GrPacketMasks layout");
static_assert(sizeof(GrCullFrame) == 48, "GrCullFrame layout");
static_assert(sizeof(GrVoxelBox) == 24, "GrVoxelBox layout");
#endif

#endif
