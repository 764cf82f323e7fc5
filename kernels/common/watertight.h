/* Watertight ray/triangle test of Woop, Benthin & Wald (2013), "Watertight Ray/Triangle
 * Intersection", JCGT 2(1). Shared by the host (C++) and the kernels (OpenCL C 1.2).
 *
 * The ray is sheared so that it becomes the +z axis of a ray-local frame (kz = the
 * dominant axis of d); the triangle's vertices, relative to the origin, are projected
 * into that frame and the three 2D edge functions U, V, W are evaluated at the origin.
 * The projected coordinates of a vertex depend only on the vertex and the ray, and an
 * edge function of the shared edge of two triangles is computed from the same operands
 * in the opposite order, so its value is exactly negated (FP_CONTRACT OFF, no FMA):
 * a ray through a shared edge or vertex cannot slip between the triangles. Edges are
 * closed (U, V, W == 0 counts as inside), both windings are accepted (no culling).
 * When an edge function is exactly 0 in float (cancellation or underflow), it is
 * recomputed from exact double products (every float product is exact in double), so
 * its sign is the exact sign; on a device without cl_khr_fp64 the float value stays.
 *
 * Watertightness needs the SAME float vertices on both sides of an edge. The default
 * triangle layout (GrTriangle: v0, e1 = v1 - v0, e2 = v2 - v0) rebuilds v1 as v0 + e1,
 * which differs from v1 whenever v1 - v0 rounded (coordinates of different sign or of
 * magnitudes more than 2x apart), and two triangles sharing v1 then disagree about it.
 * Define GR_TRIANGLE_VERTICES to pass the vertices v1, v2 themselves in place of e1, e2
 * (the watertight layout: docs/accuracy.md).
 *
 * Outputs: t (ray parameter, d unit length), u, v the barycentrics of vertices 1 and 2,
 * as gr_intersect_mt. The caller checks t against its own (tmin, best) interval. */
#ifndef GRIDRT_WATERTIGHT_H
#define GRIDRT_WATERTIGHT_H
#include "gridrt_types.h"
#ifndef __OPENCL_C_VERSION__
#include <math.h>
#endif

/* GR_WT_WIDE: the type of the exact fallback of an edge function that is 0 in float. */
#ifdef __OPENCL_C_VERSION__
#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define GR_WT_WIDE double
#else
#define GR_WT_WIDE float
#endif
#else
#define GR_WT_WIDE double
#endif

/* The 2D edge function ax*by - ay*bx; exact sign (double products) when it is 0 in float. */
GR_FN float gr_wt_edge(float ax, float ay, float bx, float by) {
  float e = ax * by - ay * bx;
  if (e == 0.0f) {
    GR_WT_WIDE w = (GR_WT_WIDE)ax * (GR_WT_WIDE)by - (GR_WT_WIDE)ay * (GR_WT_WIDE)bx;
    e = (float)w;
  }
  return e;
}

/* The dominant axis of d (index 0, 1, 2); ties go to the later axis. */
GR_FN int gr_wt_major_axis(float dx, float dy, float dz) {
  float ax = fabs(dx), ay = fabs(dy), az = fabs(dz);
  return (ax > ay) ? ((ax > az) ? 0 : 2) : ((ay > az) ? 1 : 2);
}

GR_FN float gr_wt_pick(int k, float x, float y, float z) { return k == 0 ? x : (k == 1 ? y : z); }

/* The test on three vertices a, b, c (the watertight core). */
GR_FN int gr_intersect_watertight_vertices(float ox, float oy, float oz, float dx, float dy,
                                           float dz, float ax, float ay, float az, float bx,
                                           float by, float bz, float cx, float cy, float cz,
                                           float* t_out, float* u_out, float* v_out) {
  /* Ray-local frame: kz the dominant axis, kx/ky the others, swapped to keep winding. */
  int kz = gr_wt_major_axis(dx, dy, dz);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  float dkz = gr_wt_pick(kz, dx, dy, dz);
  if (dkz < 0.0f) {
    int swap = kx;
    kx = ky;
    ky = swap;
  }
  float sx = gr_wt_pick(kx, dx, dy, dz) / dkz;
  float sy = gr_wt_pick(ky, dx, dy, dz) / dkz;
  float sz = 1.0f / dkz;
  /* Vertices relative to the origin, sheared and projected. */
  float rax = ax - ox, ray2 = ay - oy, raz = az - oz;
  float rbx = bx - ox, rby = by - oy, rbz = bz - oz;
  float rcx = cx - ox, rcy = cy - oy, rcz = cz - oz;
  float a_kz = gr_wt_pick(kz, rax, ray2, raz);
  float b_kz = gr_wt_pick(kz, rbx, rby, rbz);
  float c_kz = gr_wt_pick(kz, rcx, rcy, rcz);
  float pax = gr_wt_pick(kx, rax, ray2, raz) - sx * a_kz;
  float pay = gr_wt_pick(ky, rax, ray2, raz) - sy * a_kz;
  float pbx = gr_wt_pick(kx, rbx, rby, rbz) - sx * b_kz;
  float pby = gr_wt_pick(ky, rbx, rby, rbz) - sy * b_kz;
  float pcx = gr_wt_pick(kx, rcx, rcy, rcz) - sx * c_kz;
  float pcy = gr_wt_pick(ky, rcx, rcy, rcz) - sy * c_kz;
  /* Edge functions: U opposite a, V opposite b, W opposite c. */
  float eu = gr_wt_edge(pcx, pcy, pbx, pby);
  float ev = gr_wt_edge(pax, pay, pcx, pcy);
  float ew = gr_wt_edge(pbx, pby, pax, pay);
  int outside = (eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f);
  float det = eu + ev + ew;
  /* Hit distance: the barycentric mix of the vertices' scaled z. */
  float t_scaled = eu * (sz * a_kz) + ev * (sz * b_kz) + ew * (sz * c_kz);
  float inv_det = 1.0f / det;
  *t_out = t_scaled * inv_det;
  *u_out = ev * inv_det;
  *v_out = ew * inv_det;
  return !outside && det != 0.0f;
}

/* The signature of gr_intersect_mt: v0 and either the edges e1, e2 (default layout) or,
 * with GR_TRIANGLE_VERTICES, the vertices v1, v2 in their place. */
GR_FN int gr_intersect_watertight(float ox, float oy, float oz, float dx, float dy, float dz,
                                  float v0x, float v0y, float v0z, float e1x, float e1y, float e1z,
                                  float e2x, float e2y, float e2z, float* t_out, float* u_out,
                                  float* v_out) {
#ifdef GR_TRIANGLE_VERTICES
  return gr_intersect_watertight_vertices(ox, oy, oz, dx, dy, dz, v0x, v0y, v0z, e1x, e1y, e1z, e2x,
                                          e2y, e2z, t_out, u_out, v_out);
#else
  return gr_intersect_watertight_vertices(ox, oy, oz, dx, dy, dz, v0x, v0y, v0z, v0x + e1x,
                                          v0y + e1y, v0z + e1z, v0x + e2x, v0y + e2y, v0z + e2z,
                                          t_out, u_out, v_out);
#endif
}

#endif
