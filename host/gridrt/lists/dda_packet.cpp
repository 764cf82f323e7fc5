#include "dda_packet.h"

#include <cstdlib>

#include "grid_dda.h"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif
#ifdef __AVX512F__
// GCC 12's _mm512_min_ps / _mm512_max_ps pass _mm512_undefined_ps() as the unused merge
// source, which -Wuninitialized reports inside the header.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace gridrt {

#ifdef __AVX512F__

namespace {

static_assert(sizeof(ListEntry) == 3 * sizeof(int), "ListEntry is scattered as 3 ints");

// MINPS / MAXPS are a < b ? a : b and a > b ? a : b, operand order included (the second
// operand on ties and NaN), which is how grid_dda.h writes its minima and maxima.
inline __m512 lessOf(__m512 a, __m512 b) { return _mm512_min_ps(a, b); }
inline __m512 greaterOf(__m512 a, __m512 b) { return _mm512_max_ps(a, b); }

inline __mmask16 isFinite(__m512 x) {  // x - x is 0 for finite x, NaN otherwise
  return _mm512_cmp_ps_mask(_mm512_sub_ps(x, x), _mm512_setzero_ps(), _CMP_EQ_OQ);
}

// One axis of the walk: its origin, direction, reciprocal, step, voxel index and the
// distance to the voxel's far boundary, lane by lane.
struct Axis {
  __m512 o, d, inv, tn;
  __m512i step, i;
  float grid_min, cell;
  int n;

  // gr_next_boundary in every lane: (min + k * cell - o) * inv, infinite where the step
  // is 0, k = i + 1 stepping up, i stepping down.
  __m512 nextBoundary() const {
    const __mmask16 up = _mm512_cmpgt_epi32_mask(step, _mm512_setzero_si512());
    const __m512i k = _mm512_mask_add_epi32(i, up, i, _mm512_set1_epi32(1));
    const __m512 plane = _mm512_add_ps(_mm512_set1_ps(grid_min),
                                       _mm512_mul_ps(_mm512_cvtepi32_ps(k), _mm512_set1_ps(cell)));
    const __m512 t = _mm512_mul_ps(_mm512_sub_ps(plane, o), inv);
    const __mmask16 still = _mm512_cmpeq_epi32_mask(step, _mm512_setzero_si512());
    return _mm512_mask_mov_ps(t, still, _mm512_set1_ps(INFINITY));
  }
};

// gr_slab and the direction set-up of gr_dda_begin for one axis; clears the lanes of
// `valid` whose ray misses the slab [lo, hi].
void beginAxis(Axis& a, float lo, float hi, __m512& t0, __m512& t1, __mmask16& valid) {
  const __m512 zero = _mm512_setzero_ps();
  const __m512 tiny = _mm512_set1_ps(GR_FLT_MIN);
  // A subnormal component is walked as +0.
  const __mmask16 subnormal = _mm512_cmp_ps_mask(a.d, _mm512_sub_ps(zero, tiny), _CMP_GT_OQ) &
                              _mm512_cmp_ps_mask(a.d, tiny, _CMP_LT_OQ);
  a.d = _mm512_mask_mov_ps(a.d, subnormal, zero);
  const __mmask16 flat = _mm512_cmp_ps_mask(a.d, zero, _CMP_EQ_OQ);
  const __mmask16 outside = _mm512_cmp_ps_mask(a.o, _mm512_set1_ps(lo), _CMP_LT_OQ) |
                            _mm512_cmp_ps_mask(a.o, _mm512_set1_ps(hi), _CMP_GT_OQ);
  valid &= ~(flat & outside);
  const __m512 inv = _mm512_div_ps(_mm512_set1_ps(1.0f), a.d);
  const __m512 p = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(lo), a.o), inv);
  const __m512 q = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(hi), a.o), inv);
  const __m512 near = _mm512_mask_mov_ps(lessOf(p, q), flat, _mm512_set1_ps(-INFINITY));
  const __m512 far = _mm512_mask_mov_ps(greaterOf(q, p), flat, _mm512_set1_ps(INFINITY));
  t0 = greaterOf(near, t0);
  t1 = lessOf(far, t1);
  const __mmask16 positive = _mm512_cmp_ps_mask(a.d, zero, _CMP_GT_OQ);
  const __mmask16 negative = _mm512_cmp_ps_mask(a.d, zero, _CMP_LT_OQ);
  a.step = _mm512_mask_mov_epi32(_mm512_setzero_si512(), positive, _mm512_set1_epi32(1));
  a.step = _mm512_mask_mov_epi32(a.step, negative, _mm512_set1_epi32(-1));
  a.inv = _mm512_mask_mov_ps(zero, ~flat, inv);
}

// The entry voxel's index on one axis: floor((p - min) / cell), clamped into the grid.
void entryIndex(Axis& a, __m512 t0) {
  const __m512 p = _mm512_add_ps(a.o, _mm512_mul_ps(t0, a.d));
  const __m512 cell =
      _mm512_div_ps(_mm512_sub_ps(p, _mm512_set1_ps(a.grid_min)), _mm512_set1_ps(a.cell));
  const __m512i i =
      _mm512_cvttps_epi32(_mm512_roundscale_ps(cell, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
  a.i = _mm512_min_epi32(_mm512_max_epi32(i, _mm512_setzero_si512()), _mm512_set1_epi32(a.n - 1));
}

// gr_dda_update_exit.
__m512 exitOf(const Axis& x, const Axis& y, const Axis& z, __m512 t_end, __m512 t_enter) {
  __m512 t = lessOf(x.tn, y.tn);
  t = lessOf(t, z.tn);
  t = lessOf(t, t_end);
  return greaterOf(t, t_enter);
}

// Steps the lanes of `sel` along axis a; returns those that left the grid.
__mmask16 stepAxis(Axis& a, __mmask16 sel) {
  a.i = _mm512_mask_add_epi32(a.i, sel, a.i, a.step);
  const __mmask16 left = _mm512_mask_cmplt_epi32_mask(sel, a.i, _mm512_setzero_si512()) |
                         _mm512_mask_cmpge_epi32_mask(sel, a.i, _mm512_set1_epi32(a.n));
  a.tn = _mm512_mask_mov_ps(a.tn, sel & ~left, a.nextBoundary());
  return left;
}

}  // namespace

void ddaPacket(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
               ListEntry* out, int stride, int* counts) {
  const __mmask16 lanes = count >= 16 ? 0xFFFF : __mmask16((1u << count) - 1u);
  const __m512i lane = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
  const float* ray_floats = reinterpret_cast<const float*>(rays);
  auto field = [&](int f) {  // field f of the 8 floats of each lane's GrRay
    const __m512i at = _mm512_add_epi32(_mm512_slli_epi32(lane, 3), _mm512_set1_epi32(f));
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, at, ray_floats, 4);
  };
  Axis x{field(0), field(4), {}, {}, {}, {}, g.minx, g.cellx, g.nx};
  Axis y{field(1), field(5), {}, {}, {}, {}, g.miny, g.celly, g.ny};
  Axis z{field(2), field(6), {}, {}, {}, {}, g.minz, g.cellz, g.nz};
  __mmask16 valid = lanes & isFinite(x.o) & isFinite(y.o) & isFinite(z.o) & isFinite(x.d) &
                    isFinite(y.d) & isFinite(z.d);
  __m512 t0 = field(3), t1 = field(7);
  beginAxis(x, g.minx, g.minx + float(g.nx) * g.cellx, t0, t1, valid);
  beginAxis(y, g.miny, g.miny + float(g.ny) * g.celly, t0, t1, valid);
  beginAxis(z, g.minz, g.minz + float(g.nz) * g.cellz, t0, t1, valid);
  valid &= _mm512_cmp_ps_mask(t0, t1, _CMP_LE_OQ);
  for (Axis* a : {&x, &y, &z}) {
    entryIndex(*a, t0);
    a->tn = a->nextBoundary();
  }
  const __m512 t_end = t1;
  __m512 t_enter = t0;
  __m512 t_exit = exitOf(x, y, z, t_end, t_enter);

  int* out_ints = reinterpret_cast<int*>(out);
  const __m512i lane_base = _mm512_mullo_epi32(lane, _mm512_set1_epi32(stride));
  __m512i found = _mm512_setzero_si512();
  const __m512i one = _mm512_set1_epi32(1);
  for (__mmask16 active = valid; active;) {
    // The current voxel, kept when it holds a PE: (pe, t_enter, t_exit) as 3 ints.
    const __m512i voxel = _mm512_add_epi32(
        x.i, _mm512_mullo_epi32(
                 _mm512_set1_epi32(g.nx),
                 _mm512_add_epi32(y.i, _mm512_mullo_epi32(_mm512_set1_epi32(g.ny), z.i))));
    const __m512i pe =
        _mm512_mask_i32gather_epi32(_mm512_set1_epi32(-1), active, voxel, pe_of_voxel, 4);
    const __mmask16 keep = _mm512_mask_cmpge_epi32_mask(active, pe, _mm512_setzero_si512());
    const __m512i at = _mm512_mullo_epi32(_mm512_add_epi32(lane_base, found), _mm512_set1_epi32(3));
    _mm512_mask_i32scatter_epi32(out_ints, keep, at, pe, 4);
    _mm512_mask_i32scatter_ps(out_ints, keep, _mm512_add_epi32(at, one), t_enter, 4);
    _mm512_mask_i32scatter_ps(out_ints, keep, _mm512_add_epi32(at, _mm512_set1_epi32(2)), t_exit,
                              4);
    found = _mm512_mask_add_epi32(found, keep, found, one);

    // gr_dda_step: stop at t_end, else step the nearest boundary's axis (x, y, z on ties).
    __mmask16 go = active & ~_mm512_cmp_ps_mask(t_exit, t_end, _CMP_GE_OQ);
    const __mmask16 sel_x = go & _mm512_cmp_ps_mask(x.tn, y.tn, _CMP_LE_OQ) &
                            _mm512_cmp_ps_mask(x.tn, z.tn, _CMP_LE_OQ);
    const __mmask16 sel_y = go & ~sel_x & _mm512_cmp_ps_mask(y.tn, z.tn, _CMP_LE_OQ);
    const __mmask16 sel_z = go & ~sel_x & ~sel_y;
    go &= ~(stepAxis(x, sel_x) | stepAxis(y, sel_y) | stepAxis(z, sel_z));
    t_enter = _mm512_mask_mov_ps(t_enter, go, t_exit);
    t_exit = _mm512_mask_mov_ps(t_exit, go, exitOf(x, y, z, t_end, t_enter));
    active = go;
  }
  alignas(64) int found_lanes[16];
  _mm512_store_si512(found_lanes, found);
  for (int k = 0; k < count; ++k) counts[k] = found_lanes[k];
}

#elif defined(__AVX2__)

namespace {

// The same walk as the AVX-512 version above, 8 lanes a packet: masks are vectors (all
// bits set in a lane where true), blends replace masked moves, and the kept voxels are
// written lane by lane (AVX2 has gathers but no scatter).
inline __m256 lessOf(__m256 a, __m256 b) { return _mm256_min_ps(a, b); }
inline __m256 greaterOf(__m256 a, __m256 b) { return _mm256_max_ps(a, b); }
inline __m256 asFloat(__m256i m) { return _mm256_castsi256_ps(m); }
inline __m256i asInt(__m256 m) { return _mm256_castps_si256(m); }

inline __m256 isFinite(__m256 x) {  // x - x is 0 for finite x, NaN otherwise
  return _mm256_cmp_ps(_mm256_sub_ps(x, x), _mm256_setzero_ps(), _CMP_EQ_OQ);
}

struct Axis {
  __m256 o, d, inv, tn;
  __m256i step, i;
  float grid_min, cell;
  int n;

  __m256 nextBoundary() const {
    const __m256i up = _mm256_cmpgt_epi32(step, _mm256_setzero_si256());
    const __m256i k = _mm256_sub_epi32(i, up);  // i + 1 where stepping up (up is -1 there)
    const __m256 plane = _mm256_add_ps(_mm256_set1_ps(grid_min),
                                       _mm256_mul_ps(_mm256_cvtepi32_ps(k), _mm256_set1_ps(cell)));
    const __m256 t = _mm256_mul_ps(_mm256_sub_ps(plane, o), inv);
    const __m256i still = _mm256_cmpeq_epi32(step, _mm256_setzero_si256());
    return _mm256_blendv_ps(t, _mm256_set1_ps(INFINITY), asFloat(still));
  }
};

void beginAxis(Axis& a, float lo, float hi, __m256& t0, __m256& t1, __m256& valid) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 tiny = _mm256_set1_ps(GR_FLT_MIN);
  const __m256 subnormal = _mm256_and_ps(_mm256_cmp_ps(a.d, _mm256_sub_ps(zero, tiny), _CMP_GT_OQ),
                                         _mm256_cmp_ps(a.d, tiny, _CMP_LT_OQ));
  a.d = _mm256_blendv_ps(a.d, zero, subnormal);
  const __m256 flat = _mm256_cmp_ps(a.d, zero, _CMP_EQ_OQ);
  const __m256 outside = _mm256_or_ps(_mm256_cmp_ps(a.o, _mm256_set1_ps(lo), _CMP_LT_OQ),
                                      _mm256_cmp_ps(a.o, _mm256_set1_ps(hi), _CMP_GT_OQ));
  valid = _mm256_andnot_ps(_mm256_and_ps(flat, outside), valid);
  const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), a.d);
  const __m256 p = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(lo), a.o), inv);
  const __m256 q = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(hi), a.o), inv);
  const __m256 near = _mm256_blendv_ps(lessOf(p, q), _mm256_set1_ps(-INFINITY), flat);
  const __m256 far = _mm256_blendv_ps(greaterOf(q, p), _mm256_set1_ps(INFINITY), flat);
  t0 = greaterOf(near, t0);
  t1 = lessOf(far, t1);
  const __m256i positive = asInt(_mm256_cmp_ps(a.d, zero, _CMP_GT_OQ));
  const __m256i negative = asInt(_mm256_cmp_ps(a.d, zero, _CMP_LT_OQ));
  a.step = _mm256_or_si256(_mm256_and_si256(positive, _mm256_set1_epi32(1)), negative);
  a.inv = _mm256_blendv_ps(inv, zero, flat);
}

void entryIndex(Axis& a, __m256 t0) {
  const __m256 p = _mm256_add_ps(a.o, _mm256_mul_ps(t0, a.d));
  const __m256 cell =
      _mm256_div_ps(_mm256_sub_ps(p, _mm256_set1_ps(a.grid_min)), _mm256_set1_ps(a.cell));
  const __m256i i = _mm256_cvttps_epi32(_mm256_floor_ps(cell));
  a.i = _mm256_min_epi32(_mm256_max_epi32(i, _mm256_setzero_si256()), _mm256_set1_epi32(a.n - 1));
}

__m256 exitOf(const Axis& x, const Axis& y, const Axis& z, __m256 t_end, __m256 t_enter) {
  __m256 t = lessOf(x.tn, y.tn);
  t = lessOf(t, z.tn);
  t = lessOf(t, t_end);
  return greaterOf(t, t_enter);
}

// Steps the lanes of `sel` along axis a; returns those that left the grid.
__m256 stepAxis(Axis& a, __m256 sel) {
  a.i = _mm256_add_epi32(a.i, _mm256_and_si256(a.step, asInt(sel)));
  const __m256i out = _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), a.i),
                                      _mm256_cmpgt_epi32(a.i, _mm256_set1_epi32(a.n - 1)));
  const __m256 left = _mm256_and_ps(sel, asFloat(out));
  a.tn = _mm256_blendv_ps(a.tn, a.nextBoundary(), _mm256_andnot_ps(left, sel));
  return left;
}

}  // namespace

void ddaPacket(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
               ListEntry* out, int stride, int* counts) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256 lanes = asFloat(_mm256_cmpgt_epi32(_mm256_set1_epi32(count), lane));
  const float* ray_floats = reinterpret_cast<const float*>(rays);
  auto field = [&](int f) {  // field f of the 8 floats of each lane's GrRay
    const __m256i at = _mm256_add_epi32(_mm256_slli_epi32(lane, 3), _mm256_set1_epi32(f));
    return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), ray_floats, at, lanes, 4);
  };
  Axis x{field(0), field(4), {}, {}, {}, {}, g.minx, g.cellx, g.nx};
  Axis y{field(1), field(5), {}, {}, {}, {}, g.miny, g.celly, g.ny};
  Axis z{field(2), field(6), {}, {}, {}, {}, g.minz, g.cellz, g.nz};
  __m256 valid = _mm256_and_ps(
      lanes, _mm256_and_ps(_mm256_and_ps(isFinite(x.o), isFinite(y.o)), isFinite(z.o)));
  valid = _mm256_and_ps(valid,
                        _mm256_and_ps(_mm256_and_ps(isFinite(x.d), isFinite(y.d)), isFinite(z.d)));
  __m256 t0 = field(3), t1 = field(7);
  beginAxis(x, g.minx, g.minx + float(g.nx) * g.cellx, t0, t1, valid);
  beginAxis(y, g.miny, g.miny + float(g.ny) * g.celly, t0, t1, valid);
  beginAxis(z, g.minz, g.minz + float(g.nz) * g.cellz, t0, t1, valid);
  valid = _mm256_and_ps(valid, _mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
  for (Axis* a : {&x, &y, &z}) {
    entryIndex(*a, t0);
    a->tn = a->nextBoundary();
  }
  const __m256 t_end = t1;
  __m256 t_enter = t0;
  __m256 t_exit = exitOf(x, y, z, t_end, t_enter);

  __m256i found = _mm256_setzero_si256();
  alignas(32) int pe_of[8], found_of[8];
  alignas(32) float enter_of[8], exit_of[8];
  for (__m256 active = valid; _mm256_movemask_ps(active);) {
    // The current voxel, kept when it holds a PE.
    const __m256i voxel = _mm256_add_epi32(
        x.i, _mm256_mullo_epi32(
                 _mm256_set1_epi32(g.nx),
                 _mm256_add_epi32(y.i, _mm256_mullo_epi32(_mm256_set1_epi32(g.ny), z.i))));
    const __m256i pe =
        _mm256_mask_i32gather_epi32(_mm256_set1_epi32(-1), pe_of_voxel, voxel, asInt(active), 4);
    const __m256i keep =
        _mm256_and_si256(asInt(active), _mm256_cmpgt_epi32(pe, _mm256_set1_epi32(-1)));
    if (int kept = _mm256_movemask_ps(asFloat(keep))) {
      _mm256_store_si256(reinterpret_cast<__m256i*>(pe_of), pe);
      _mm256_store_si256(reinterpret_cast<__m256i*>(found_of), found);
      _mm256_store_ps(enter_of, t_enter);
      _mm256_store_ps(exit_of, t_exit);
      for (; kept; kept &= kept - 1) {
        const int k = __builtin_ctz(unsigned(kept));
        out[size_t(k) * stride + found_of[k]] = ListEntry{pe_of[k], enter_of[k], exit_of[k]};
      }
      found = _mm256_sub_epi32(found, keep);  // + 1 where kept (keep is -1 there)
    }

    // gr_dda_step: stop at t_end, else step the nearest boundary's axis (x, y, z on ties).
    __m256 go = _mm256_andnot_ps(_mm256_cmp_ps(t_exit, t_end, _CMP_GE_OQ), active);
    const __m256 sel_x = _mm256_and_ps(go, _mm256_and_ps(_mm256_cmp_ps(x.tn, y.tn, _CMP_LE_OQ),
                                                         _mm256_cmp_ps(x.tn, z.tn, _CMP_LE_OQ)));
    const __m256 sel_y =
        _mm256_and_ps(_mm256_andnot_ps(sel_x, go), _mm256_cmp_ps(y.tn, z.tn, _CMP_LE_OQ));
    const __m256 sel_z = _mm256_andnot_ps(_mm256_or_ps(sel_x, sel_y), go);
    const __m256 left_x = stepAxis(x, sel_x);
    const __m256 left_y = stepAxis(y, sel_y);
    const __m256 left_z = stepAxis(z, sel_z);
    go = _mm256_andnot_ps(_mm256_or_ps(left_x, _mm256_or_ps(left_y, left_z)), go);
    t_enter = _mm256_blendv_ps(t_enter, t_exit, go);
    t_exit = _mm256_blendv_ps(t_exit, exitOf(x, y, z, t_end, t_enter), go);
    active = go;
  }
  _mm256_store_si256(reinterpret_cast<__m256i*>(found_of), found);
  for (int k = 0; k < count; ++k) counts[k] = found_of[k];
}

#else

void ddaPacket(const GrGridInfo&, const int*, const GrRay*, int, ListEntry*, int, int*) {
  std::abort();  // callers check kDdaPacketLanes
}

#endif

}  // namespace gridrt
