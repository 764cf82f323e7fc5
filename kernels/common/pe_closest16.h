/* Phase 1 of GridRT for 16 rays in one PE, shared by both PE kernels: each active lane
 * keeps its closest hit among the PE's triangles [begin, end) that lies in (tmin, tmax)
 * and INSIDE the voxel (t_enter <= t <= t_exit). On equal t the earlier triangle (lower
 * global index: a PE's triangles are in global order) stays. With any_hit the loop stops
 * once every active lane has a hit. best_prim is -1 where a lane found none.
 * With cull, triangle i is skipped when its box (cull_planes, CullPlaneCache) misses
 * packet_box (amin, amax, bmin, bmax of the active lanes on the tangent plane;
 * host/gridrt/culling/packet_culling.h): the boxes are grown by the test's rounding, so no triangle
 * a lane could hit is skipped. With seg->enabled (rays with their own origins), triangle i is
 * skipped when its outline and the packet's in-voxel segments, both projected across the packet's
 * mean direction, are further apart than a bound on the test's rounding
 * (host/gridrt/culling/segment_culling.h). tests_out: the ray-triangle tests it ran, the triangles
 * left after culling times the active lanes. */
#ifndef GRIDRT_PE_CLOSEST16_H
#define GRIDRT_PE_CLOSEST16_H
#include "gridrt_types.h"
#include "ray_triangle16.h"

/* Chunks of 16 triangles culled, and their survivors fetched, before the first is tested. */
#ifndef GR_CULL_WINDOW
#define GR_CULL_WINDOW 8
#endif

/* Each lane's own index, 0 .. 15. */
#define GR_LANE_INDEX16 ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))

/* The lanes of a mask (-1 per lane) as 16 bits, lane k in bit k. OpenCL C 1.2 has no
 * horizontal reduction: the disjoint bits are folded by halves. */
inline int gr_lane_bits16(int16 mask) {
  int16 b = mask & ((int16)1 << GR_LANE_INDEX16);
  int8 b8 = b.lo | b.hi;
  int4 b4 = b8.lo | b8.hi;
  int2 b2 = b4.lo | b4.hi;
  return b2.x | b2.y;
}

/* The smallest, largest and sum of 16 lanes, folded by halves. */
inline float gr_lane_min16(float16 x) {
  float8 m8 = fmin(x.lo, x.hi);
  float4 m4 = fmin(m8.lo, m8.hi);
  float2 m2 = fmin(m4.lo, m4.hi);
  return fmin(m2.x, m2.y);
}
inline float gr_lane_max16(float16 x) {
  float8 m8 = fmax(x.lo, x.hi);
  float4 m4 = fmax(m8.lo, m8.hi);
  float2 m2 = fmax(m4.lo, m4.hi);
  return fmax(m2.x, m2.y);
}
inline float gr_lane_sum16(float16 x) {
  float8 s8 = x.lo + x.hi;
  float4 s4 = s8.lo + s8.hi;
  float2 s2 = s4.lo + s4.hi;
  return s2.x + s2.y;
}

/* Segment culling's view of one packet (host/gridrt/culling/segment_culling.h). */
typedef struct {
  float ax, ay, az, bx, by, bz; /* two orthonormal axes across the lanes' mean direction */
  float amin, amax, bmin, bmax; /* the box of the lanes' segments [t_lo, t_hi] on them */
  float dcx, dcy, dcz;          /* the lanes' direction box: centre ... */
  float drx, dry, drz;          /* ... and half size */
  float reach;                  /* the largest |o|_1 + |t_hi| of a lane */
  int enabled;                  /* 0: nothing is culled */
} GrSegmentPacket;

/* The packet's summary over its active lanes, whose hits may lie only in [t_lo, t_hi]. */
inline __attribute__((always_inline)) GrSegmentPacket gr_segment_packet16(const GrRays16* r,
                                                                          float16 t_lo,
                                                                          float16 t_hi,
                                                                          int16 active) {
  GrSegmentPacket s;
  const float16 zero = 0.0f, inf = INFINITY;
  float mx = gr_lane_sum16(select(zero, r->dx, active));
  float my = gr_lane_sum16(select(zero, r->dy, active));
  float mz = gr_lane_sum16(select(zero, r->dz, active));
  const float length = sqrt(mx * mx + my * my + mz * mz);
  s.enabled = length > 0.0f && isfinite(length);
  if (!s.enabled) return s;
  mx /= length;
  my /= length;
  mz /= length;
  /* An orthonormal pair across (mx, my, mz) without a branch on the axes (Duff et al. 2017);
   * its rounding only moves the projection, which the margin covers. */
  const float sign = mz >= 0.0f ? 1.0f : -1.0f;
  const float k = -1.0f / (sign + mz), b = mx * my * k;
  s.ax = 1.0f + sign * mx * mx * k;
  s.ay = sign * b;
  s.az = -sign * mx;
  s.bx = b;
  s.by = sign + my * my * k;
  s.bz = -my;
  const float16 ao = r->ox * s.ax + r->oy * s.ay + r->oz * s.az;
  const float16 ad = r->dx * s.ax + r->dy * s.ay + r->dz * s.az;
  const float16 bo = r->ox * s.bx + r->oy * s.by + r->oz * s.bz;
  const float16 bd = r->dx * s.bx + r->dy * s.by + r->dz * s.bz;
  const float16 a0 = ao + t_lo * ad, a1 = ao + t_hi * ad;
  const float16 b0 = bo + t_lo * bd, b1 = bo + t_hi * bd;
  s.amin = gr_lane_min16(select(inf, fmin(a0, a1), active));
  s.amax = gr_lane_max16(select(-inf, fmax(a0, a1), active));
  s.bmin = gr_lane_min16(select(inf, fmin(b0, b1), active));
  s.bmax = gr_lane_max16(select(-inf, fmax(b0, b1), active));
  const float dx0 = gr_lane_min16(select(inf, r->dx, active));
  const float dx1 = gr_lane_max16(select(-inf, r->dx, active));
  const float dy0 = gr_lane_min16(select(inf, r->dy, active));
  const float dy1 = gr_lane_max16(select(-inf, r->dy, active));
  const float dz0 = gr_lane_min16(select(inf, r->dz, active));
  const float dz1 = gr_lane_max16(select(-inf, r->dz, active));
  s.dcx = 0.5f * (dx0 + dx1);
  s.dcy = 0.5f * (dy0 + dy1);
  s.dcz = 0.5f * (dz0 + dz1);
  s.drx = 0.5f * (dx1 - dx0);
  s.dry = 0.5f * (dy1 - dy0);
  s.drz = 0.5f * (dz1 - dz0);
  s.reach =
      gr_lane_max16(select(zero, fabs(r->ox) + fabs(r->oy) + fabs(r->oz) + fabs(t_hi), active));
  s.enabled = isfinite(s.reach) && isfinite(s.amin + s.amax + s.bmin + s.bmax);
  return s;
}

/* The triangles [chunk, chunk + 16) that segment culling skips for the packet, as 16 bits:
 * their projected outlines lie further from the packet's box than the margin
 * GR_SEG_ERROR * K * (reach of the packet + reach of the triangle), K = |e1| |e2| / |d.n|
 * bounded over the packet's direction box, and K <= GR_SEG_MAX_CONDITIONING. */
inline __attribute__((always_inline)) int gr_segment_culled16(const GrSegmentPacket* s,
                                                              __global const float* planes,
                                                              int stride, int chunk) {
  __global const float* q = planes + chunk;
  const float16 x0 = vload16(0, q + GR_SEG_V0X * stride), y0 = vload16(0, q + GR_SEG_V0Y * stride);
  const float16 z0 = vload16(0, q + GR_SEG_V0Z * stride), x1 = vload16(0, q + GR_SEG_V1X * stride);
  const float16 y1 = vload16(0, q + GR_SEG_V1Y * stride), z1 = vload16(0, q + GR_SEG_V1Z * stride);
  const float16 x2 = vload16(0, q + GR_SEG_V2X * stride), y2 = vload16(0, q + GR_SEG_V2Y * stride);
  const float16 z2 = vload16(0, q + GR_SEG_V2Z * stride);
  const float16 a0 = x0 * s->ax + y0 * s->ay + z0 * s->az;
  const float16 a1 = x1 * s->ax + y1 * s->ay + z1 * s->az;
  const float16 a2 = x2 * s->ax + y2 * s->ay + z2 * s->az;
  const float16 b0 = x0 * s->bx + y0 * s->by + z0 * s->bz;
  const float16 b1 = x1 * s->bx + y1 * s->by + z1 * s->bz;
  const float16 b2 = x2 * s->bx + y2 * s->by + z2 * s->bz;
  const float16 gap_a = fmax(fmin(a0, fmin(a1, a2)) - s->amax, s->amin - fmax(a0, fmax(a1, a2)));
  const float16 gap_b = fmax(fmin(b0, fmin(b1, b2)) - s->bmax, s->bmin - fmax(b0, fmax(b1, b2)));
  const float16 gap = fmax(gap_a, gap_b);
  const float16 nx = vload16(0, q + GR_SEG_NX * stride), ny = vload16(0, q + GR_SEG_NY * stride);
  const float16 nz = vload16(0, q + GR_SEG_NZ * stride);
  const float16 scale = vload16(0, q + GR_SEG_SCALE * stride);
  const float16 reach = vload16(0, q + GR_SEG_REACH * stride);
  /* The smallest |d.n| over the direction box (interval arithmetic; <= 0: grazing). */
  const float16 facing = fabs(nx * s->dcx + ny * s->dcy + nz * s->dcz) -
                         (fabs(nx) * s->drx + fabs(ny) * s->dry + fabs(nz) * s->drz);
  const int16 culled = (facing * GR_SEG_MAX_CONDITIONING >= scale) &
                       (gap * facing > GR_SEG_ERROR * scale * (reach + s->reach));
  return gr_lane_bits16(culled);
}

inline __attribute__((always_inline)) void gr_pe_closest16(
    const GrRays16* r, const GrPeGeometry* pe, float16 tmin, float16 tmax, float16 t_enter,
    float16 t_exit, int16 active, int any_hit, float4 packet_box, int cull,
    const GrSegmentPacket* seg, GrHits16* best_out, int* tests_out) {
  __global const GrTriangle* tris = pe->tris;
  const int begin = pe->begin, end = pe->end;
  __global const float* cull_planes = pe->cull_planes;
  const int cull_stride = pe->cull_stride;
  __global const float* seg_planes = pe->seg_planes;
  const int seg_stride = pe->seg_stride;
  int tested = 0;
  float16 best_t = tmax, best_u = 0.0f, best_v = 0.0f;
  int16 best_prim = -1;
  /* The packet's summary costs about what a few triangles do: small PEs skip it. */
  const int seg_cull = seg->enabled && end - begin >= GR_SEG_MIN_TRIANGLES;
  /* Triangles go in chunks of 16: first a mask of the ones to test, from 16 boxes at
   * once (a culling branch per triangle would be a mispredicted branch about as dear as
   * the test it saves), then the set bits in increasing order (the tie rule). The masks of
   * GR_CULL_WINDOW chunks are made first and their triangles fetched before the first is
   * tested: on a scene larger than the cache a PE's triangles are cold, and the first load
   * of each was the kernel's largest stall (perf, a row of 16 bunnies: 30 % of the kernel's
   * samples with no fetch ahead, 17 % with a chunk's fetch just before its tests). */
  for (int window = begin; window < end; window += GR_CULL_WINDOW * 16) {
    uint todo[GR_CULL_WINDOW];
    const int chunks = min(GR_CULL_WINDOW, (end - window + 15) / 16);
    for (int c = 0; c < chunks; ++c) {
      const int chunk = window + 16 * c;
      const int n = min(16, end - chunk);
      uint mask = (1u << n) - 1u;
      if (cull) {
        /* Box planes (amin, amax, bmin, bmax), each cull_stride long and padded by 16. */
        const float16 amin = vload16(0, cull_planes + chunk);
        const float16 amax = vload16(0, cull_planes + cull_stride + chunk);
        const float16 bmin = vload16(0, cull_planes + 2 * cull_stride + chunk);
        const float16 bmax = vload16(0, cull_planes + 3 * cull_stride + chunk);
        const int16 miss = (amax < packet_box.s0) | (amin > packet_box.s1) |
                           (bmax < packet_box.s2) | (bmin > packet_box.s3);
        mask &= ~(uint)gr_lane_bits16(miss);
      }
      if (seg_cull) mask &= ~(uint)gr_segment_culled16(seg, seg_planes, seg_stride, chunk);
#ifdef GR_CPU_DEVICE
      /* A triangle may straddle two cache lines: both ends are fetched. Only on a CPU
       * device (the host defines GR_CPU_DEVICE): GPU compilers (NVIDIA's) refuse
       * __builtin_prefetch of a __global pointer. */
      for (uint ahead = mask; ahead; ahead &= ahead - 1u) {
        __global const char* at =
            (__global const char*)(tris + chunk + 31 - clz(ahead & (0u - ahead)));
        __builtin_prefetch(at);
        __builtin_prefetch(at + sizeof(GrTriangle) - 1);
      }
#endif
      todo[c] = mask;
    }
    for (int c = 0; c < chunks; ++c) {
      const int chunk = window + 16 * c;
      uint mask = todo[c];
      while (mask) {
        const int i = chunk + 31 - clz(mask & (0u - mask));
        mask &= mask - 1u;
        GrTriangle tri = tris[i];
        ++tested;
        float16 t, u, v;
        int16 hit = gr_intersect16(r, &tri, &t, &u, &v);
        /* The in-voxel rule: without it a triangle spanning voxels could win in a PE that
         * comes before the voxel where its hit really lies. */
        hit &= active & (t > tmin) & (t < best_t) & (t >= t_enter) & (t <= t_exit);
        best_t = select(best_t, t, hit);
        best_u = select(best_u, u, hit);
        best_v = select(best_v, v, hit);
        best_prim = select(best_prim, (int16)tri.prim, hit);
        if (any_hit && all((best_prim >= 0) | (active == 0))) {
          window = end; /* done: leave every loop */
          c = chunks;
          break;
        }
      }
    }
  }
  best_out->t = best_t;
  best_out->u = best_u;
  best_out->v = best_v;
  best_out->prim = best_prim;
  *tests_out = tested * popcount(gr_lane_bits16(active));
}

/* Phase 1's output for one packet, for both PE kernels: where a lane hits, the packet's
 * t, prim, u and v planes go whole to its lanes [out, out + 16) of the result planes
 * (GR_RESULT_*, each lanes_total long). Returns the hit mask. */
inline __attribute__((always_inline)) int gr_store_packet_hits(const GrHits16* best,
                                                               const GrPacketOutput* o, int out) {
  const int hit = gr_lane_bits16(best->prim >= 0);
  if (!hit) return 0;
  __global float* results = o->results;
  const size_t lanes_total = (size_t)o->lanes_total;
  vstore16(best->t, 0, results + GR_RESULT_T * lanes_total + out);
  vstore16(best->prim, 0, (__global int*)(results + GR_RESULT_PRIM * lanes_total) + out);
  vstore16(best->u, 0, results + GR_RESULT_U * lanes_total + out);
  vstore16(best->v, 0, results + GR_RESULT_V * lanes_total + out);
  return hit;
}

/* The interrupt's keys after a packet's hits: each hitting lane lowers its ray's key to its
 * hit's t (as int bits): a later PE is skipped only when it starts beyond a hit, so one
 * starting exactly at it (a hit on the shared boundary) still runs and an exact tie there
 * goes to the lower triangle index, whichever PE runs first. Plain loads and stores, not
 * atomic_min: a key only ever holds the t of a real in-voxel hit of its ray, so whichever
 * store survives a race, a PE it skips starts beyond a hit and cannot hold the closest one;
 * a lost smaller key only skips less. The locked compare-and-swap loop PoCL makes of
 * atomic_min was 8.7 % of the camera kernel's samples (perf, bunny 1280x960). */

/* Lanes whose keys lie anywhere: lane k's at first_hit_key[key_of[k]] (the list kernel). */
inline __attribute__((always_inline)) void gr_lower_gathered_keys(const GrHits16* best, int hit,
                                                                  __global int* first_hit_key,
                                                                  int16 key_of) {
  int keys[16], index[16];
  vstore16(as_int16(best->t), 0, keys);
  vstore16(key_of, 0, index);
  for (int k = 0; k < 16; ++k)
    if ((hit & (1 << k)) && keys[k] < first_hit_key[index[k]]) first_hit_key[index[k]] = keys[k];
}

/* Lanes whose keys are consecutive, lane k's at keys[k] (the bundle kernel): one load and one
 * store of all 16, the lanes without a smaller hit writing back the key just read (racing
 * another PE's store, that may undo its smaller key: it only skips less). Against the
 * lane-by-lane loop above, the camera kernel's device time 0.92x (bunny 1280x960 and
 * bunny_res4 320x240, docs/performance.md). */
inline __attribute__((always_inline)) void gr_lower_consecutive_keys(const GrHits16* best,
                                                                     __global int* keys) {
  const int16 old = vload16(0, keys), t_bits = as_int16(best->t);
  const int16 lower = (best->prim >= 0) & (t_bits < old);
  if (any(lower)) vstore16(select(old, t_bits, lower), 0, keys);
}

#endif
