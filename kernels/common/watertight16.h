/* The watertight test of Woop, Benthin & Wald (2013) for 16 rays at once (float16 lanes)
 * against one triangle, for the kernels only. Same operations in the same order as
 * gr_intersect_watertight (watertight.h), lane by lane: each lane has its own dominant
 * axis, chosen with select (exact), so every lane rounds like the scalar test. Edge
 * functions that are exactly 0 in some lane are recomputed by the scalar gr_wt_edge
 * (exact double fallback) for that lane only. Returns the lane mask (-1 = hit). */
#ifndef GRIDRT_WATERTIGHT16_H
#define GRIDRT_WATERTIGHT16_H
#include "moller_trumbore16.h"
#include "watertight.h"

inline float16 gr_wt_pick16(int16 k, float16 x, float16 y, float16 z) {
  return select(select(z, y, k == 1), x, k == 0);
}

/* Each lane's dominant axis kz, the other two (swapped where d[kz] < 0, which keeps the
 * winding) and the shear constants: per ray, so made once per packet, not per triangle. */
inline void gr_wt_shear16(GrRays16* r) {
  float16 adx = fabs(r->dx), ady = fabs(r->dy), adz = fabs(r->dz);
  int16 kz = select(select((int16)2, (int16)1, ady > adz), select((int16)2, (int16)0, adx > adz),
                    adx > ady);
  int16 kx = select(kz + 1, (int16)0, kz == 2);
  int16 ky = select(kx + 1, (int16)0, kx == 2);
  float16 dkz = gr_wt_pick16(kz, r->dx, r->dy, r->dz);
  int16 flip = dkz < 0.0f;
  int16 kx2 = select(kx, ky, flip);
  ky = select(ky, kx, flip);
  kx = kx2;
  r->kx = kx;
  r->ky = ky;
  r->kz = kz;
  r->sx = gr_wt_pick16(kx, r->dx, r->dy, r->dz) / dkz;
  r->sy = gr_wt_pick16(ky, r->dx, r->dy, r->dz) / dkz;
  r->sz = 1.0f / dkz;
}

inline int16 gr_intersect_watertight16_vertices(const GrRays16* r, float ax, float ay, float az,
                                                float bx, float by, float bz, float cx, float cy,
                                                float cz, float16* t_out, float16* u_out,
                                                float16* v_out) {
  const int16 kx = r->kx, ky = r->ky, kz = r->kz;
  const float16 sx = r->sx, sy = r->sy, sz = r->sz;
  float16 rax = ax - r->ox, ray2 = ay - r->oy, raz = az - r->oz;
  float16 rbx = bx - r->ox, rby = by - r->oy, rbz = bz - r->oz;
  float16 rcx = cx - r->ox, rcy = cy - r->oy, rcz = cz - r->oz;
  float16 a_kz = gr_wt_pick16(kz, rax, ray2, raz);
  float16 b_kz = gr_wt_pick16(kz, rbx, rby, rbz);
  float16 c_kz = gr_wt_pick16(kz, rcx, rcy, rcz);
  float16 pax = gr_wt_pick16(kx, rax, ray2, raz) - sx * a_kz;
  float16 pay = gr_wt_pick16(ky, rax, ray2, raz) - sy * a_kz;
  float16 pbx = gr_wt_pick16(kx, rbx, rby, rbz) - sx * b_kz;
  float16 pby = gr_wt_pick16(ky, rbx, rby, rbz) - sy * b_kz;
  float16 pcx = gr_wt_pick16(kx, rcx, rcy, rcz) - sx * c_kz;
  float16 pcy = gr_wt_pick16(ky, rcx, rcy, rcz) - sy * c_kz;
  float16 eu = pcx * pby - pcy * pbx;
  float16 ev = pax * pcy - pay * pcx;
  float16 ew = pbx * pay - pby * pax;
  if (any((eu == 0.0f) | (ev == 0.0f) | (ew == 0.0f))) {
    /* Rare: redo the zero lanes with the scalar edge function and its double fallback. */
    float l_pax[16], l_pay[16], l_pbx[16], l_pby[16], l_pcx[16], l_pcy[16];
    float l_eu[16], l_ev[16], l_ew[16];
    vstore16(pax, 0, l_pax);
    vstore16(pay, 0, l_pay);
    vstore16(pbx, 0, l_pbx);
    vstore16(pby, 0, l_pby);
    vstore16(pcx, 0, l_pcx);
    vstore16(pcy, 0, l_pcy);
    vstore16(eu, 0, l_eu);
    vstore16(ev, 0, l_ev);
    vstore16(ew, 0, l_ew);
    for (int k = 0; k < 16; ++k) {
      if (l_eu[k] == 0.0f) l_eu[k] = gr_wt_edge(l_pcx[k], l_pcy[k], l_pbx[k], l_pby[k]);
      if (l_ev[k] == 0.0f) l_ev[k] = gr_wt_edge(l_pax[k], l_pay[k], l_pcx[k], l_pcy[k]);
      if (l_ew[k] == 0.0f) l_ew[k] = gr_wt_edge(l_pbx[k], l_pby[k], l_pax[k], l_pay[k]);
    }
    eu = vload16(0, l_eu);
    ev = vload16(0, l_ev);
    ew = vload16(0, l_ew);
  }
  int16 outside =
      ((eu < 0.0f) | (ev < 0.0f) | (ew < 0.0f)) & ((eu > 0.0f) | (ev > 0.0f) | (ew > 0.0f));
  float16 det = eu + ev + ew;
  float16 t_scaled = eu * (sz * a_kz) + ev * (sz * b_kz) + ew * (sz * c_kz);
  float16 inv_det = 1.0f / det;
  *t_out = t_scaled * inv_det;
  *u_out = ev * inv_det;
  *v_out = ew * inv_det;
  return (outside == 0) & (det != 0.0f);
}

/* The signature of gr_intersect_mt16; the triangle layout as gr_intersect_watertight. */
inline int16 gr_intersect_watertight16(const GrRays16* r, const GrTriangle* tri, float16* t_out,
                                       float16* u_out, float16* v_out) {
  const float v0x = tri->v0x, v0y = tri->v0y, v0z = tri->v0z;
  const float e1x = tri->e1x, e1y = tri->e1y, e1z = tri->e1z;
  const float e2x = tri->e2x, e2y = tri->e2y, e2z = tri->e2z;
#ifdef GR_TRIANGLE_VERTICES
  return gr_intersect_watertight16_vertices(r, v0x, v0y, v0z, e1x, e1y, e1z, e2x, e2y, e2z, t_out,
                                            u_out, v_out);
#else
  return gr_intersect_watertight16_vertices(r, v0x, v0y, v0z, v0x + e1x, v0y + e1y, v0z + e1z,
                                            v0x + e2x, v0y + e2y, v0z + e2z, t_out, u_out, v_out);
#endif
}

#endif
