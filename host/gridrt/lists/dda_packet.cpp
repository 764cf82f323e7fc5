#include "dda_packet.h"

// One target, the vector unit the build's flags select (-march=native by default): no
// dispatch at run time.
#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "grid_dda.h"

namespace gridrt {
namespace {

namespace hn = hwy::HWY_NAMESPACE;

static_assert(sizeof(GrRay) == 8 * sizeof(float), "the rays are gathered as 8 floats each");
static_assert(sizeof(ListEntry) == 3 * sizeof(int32_t), "the entries are scattered as 3 ints");

// The walk of kLanes rays, one per lane, written once for every width (Highway, the vector
// unit the build targets). Each operation is the one of grid_dda.h on every lane, with its
// operands in the same order, so that ties, signed zeros, infinities and NaN come out as
// in the scalar walk.
template <size_t kLanes>
struct PacketWalk {
  using DF = hn::FixedTag<float, kLanes>;
  using DI = hn::RebindToSigned<DF>;
  using VF = hn::VFromD<DF>;
  using VI = hn::VFromD<DI>;
  using Mask = decltype(hn::MaskFromVec(hn::Zero(DF())));

  static constexpr DF df{};
  static constexpr DI di{};

  // a < b ? a : b and a > b ? a : b, the second operand on ties and NaN, as grid_dda.h
  // writes its minima and maxima. x86's MINPS and MAXPS are defined as exactly these
  // expressions, operand order included; elsewhere a compare and a select.
  static VF lessOf(VF a, VF b) {
#if HWY_ARCH_X86
    return hn::Min(a, b);
#else
    return hn::IfThenElse(a < b, a, b);
#endif
  }
  static VF greaterOf(VF a, VF b) {
#if HWY_ARCH_X86
    return hn::Max(a, b);
#else
    return hn::IfThenElse(a > b, a, b);
#endif
  }
  static Mask asFloatMask(decltype(hn::MaskFromVec(hn::Zero(DI()))) m) {
    return hn::RebindMask(df, m);
  }
  static Mask isFinite(VF x) { return (x - x) == hn::Zero(df); }  // x - x is NaN unless finite

  // One axis of the walk: its origin, direction, reciprocal, step, voxel index and the
  // distance to the voxel's far boundary, lane by lane.
  struct Axis {
    VF o, d, inv, tn;
    VI step, i;
    float grid_min, cell;
    int n;

    // gr_next_boundary: (min + k * cell - o) * inv, k = i + 1 stepping up, i stepping
    // down, infinite where the step is 0.
    VF nextBoundary() const {
      const VI k = i + hn::IfThenElseZero(step > hn::Zero(di), hn::Set(di, 1));
      const VF plane = hn::Set(df, grid_min) + hn::ConvertTo(df, k) * hn::Set(df, cell);
      const VF t = (plane - o) * inv;
      return hn::IfThenElse(asFloatMask(step == hn::Zero(di)), hn::Set(df, HUGE_VALF), t);
    }

    // gr_slab and the direction set-up of gr_dda_begin; clears the lanes of `valid` whose
    // ray misses the slab [lo, hi].
    void begin(float lo, float hi, VF& t0, VF& t1, Mask& valid) {
      const VF zero = hn::Zero(df);
      const VF tiny = hn::Set(df, GR_FLT_MIN);
      d = hn::IfThenElse(hn::And(d > zero - tiny, d < tiny), zero, d);  // subnormal: +0
      const Mask flat = d == zero;
      const Mask outside = hn::Or(o<hn::Set(df, lo), o> hn::Set(df, hi));
      valid = hn::AndNot(hn::And(flat, outside), valid);
      const VF reciprocal = hn::Set(df, 1.0f) / d;
      const VF p = (hn::Set(df, lo) - o) * reciprocal;
      const VF q = (hn::Set(df, hi) - o) * reciprocal;
      const VF near = hn::IfThenElse(flat, hn::Set(df, -HUGE_VALF), lessOf(p, q));
      const VF far = hn::IfThenElse(flat, hn::Set(df, HUGE_VALF), greaterOf(q, p));
      t0 = greaterOf(near, t0);
      t1 = lessOf(far, t1);
      step = hn::IfThenElse(hn::RebindMask(di, d > zero), hn::Set(di, 1),
                            hn::IfThenElseZero(hn::RebindMask(di, d < zero), hn::Set(di, -1)));
      inv = hn::IfThenElseZero(hn::Not(flat), reciprocal);
    }

    // The entry voxel's index: (int)floor((p - min) / cell), clamped into the grid. The
    // conversion is done where it cannot overflow; NaN and values of 2^31 and beyond
    // become 0, as x86's conversion (0x80000000) clamped makes them in the scalar walk.
    void enter(VF t0) {
      const VF p = o + t0 * d;
      const VF cells = hn::Floor((p - hn::Set(df, grid_min)) / hn::Set(df, cell));
      const Mask in_range = hn::And(cells >= hn::Zero(df), cells < hn::Set(df, 2147483648.0f));
      const VI index =
          hn::Min(hn::ConvertTo(di, hn::IfThenElseZero(in_range, cells)), hn::Set(di, n - 1));
      i = hn::IfThenElseZero(hn::RebindMask(di, in_range), index);
      tn = nextBoundary();
    }

    // Steps the lanes of `sel`; returns those that left the grid.
    Mask advance(Mask sel) {
      const auto sel_i = hn::RebindMask(di, sel);
      i = hn::IfThenElse(sel_i, i + step, i);
      const Mask left = hn::And(sel, asFloatMask(hn::Or(i<hn::Zero(di), i> hn::Set(di, n - 1))));
      tn = hn::IfThenElse(hn::AndNot(left, sel), nextBoundary(), tn);
      return left;
    }
  };

  // gr_dda_update_exit.
  static VF exitOf(const Axis& x, const Axis& y, const Axis& z, VF t_end, VF t_enter) {
    VF t = lessOf(x.tn, y.tn);
    t = lessOf(t, z.tn);
    t = lessOf(t, t_end);
    return greaterOf(t, t_enter);
  }

  static void run(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
                  ListEntry* out, int stride, int* counts) {
    const VI lane = hn::Iota(di, 0);
    const auto lanes_i = lane < hn::Set(di, count);
    const float* ray_floats = reinterpret_cast<const float*>(rays);
    auto field = [&](int f) {  // field f of each lane's GrRay; lanes past count read ray 0
      return hn::GatherIndex(df, ray_floats,
                             hn::IfThenElseZero(lanes_i, lane * hn::Set(di, 8) + hn::Set(di, f)));
    };
    Axis x{field(0), field(4), {}, {}, {}, {}, g.minx, g.cellx, g.nx};
    Axis y{field(1), field(5), {}, {}, {}, {}, g.miny, g.celly, g.ny};
    Axis z{field(2), field(6), {}, {}, {}, {}, g.minz, g.cellz, g.nz};
    Mask valid = hn::And(asFloatMask(lanes_i),
                         hn::And(hn::And(isFinite(x.o), isFinite(y.o)), isFinite(z.o)));
    valid = hn::And(valid, hn::And(hn::And(isFinite(x.d), isFinite(y.d)), isFinite(z.d)));
    VF t0 = field(3), t1 = field(7);
    x.begin(g.minx, g.minx + float(g.nx) * g.cellx, t0, t1, valid);
    y.begin(g.miny, g.miny + float(g.ny) * g.celly, t0, t1, valid);
    z.begin(g.minz, g.minz + float(g.nz) * g.cellz, t0, t1, valid);
    valid = hn::And(valid, t0 <= t1);
    x.enter(t0);
    y.enter(t0);
    z.enter(t0);
    const VF t_end = t1;
    VF t_enter = t0;
    VF t_exit = exitOf(x, y, z, t_end, t_enter);

    int32_t* out_ints = reinterpret_cast<int32_t*>(out);
    const VI lane_base = lane * hn::Set(di, stride);
    VI found = hn::Zero(di);
    for (Mask active = valid; !hn::AllFalse(df, active);) {
      // The current voxel, kept when it holds a PE (inactive lanes read voxel 0).
      const auto active_i = hn::RebindMask(di, active);
      const VI voxel = x.i + hn::Set(di, g.nx) * (y.i + hn::Set(di, g.ny) * z.i);
      const VI pe = hn::IfThenElse(
          active_i, hn::GatherIndex(di, pe_of_voxel, hn::IfThenElseZero(active_i, voxel)),
          hn::Set(di, -1));
      const auto keep = hn::And(active_i, pe != hn::Set(di, -1));
      // Every lane writes (pe, t_enter, t_exit) to its next free slot, inside its stride (a
      // ray keeps fewer voxels than that), with one scatter per field instead of a loop
      // over the kept lanes; only the kept ones count it, the others' slot is overwritten
      // later or left past their count.
      const VI at = (lane_base + found) * hn::Set(di, 3);
      hn::ScatterIndex(pe, di, out_ints, at);
      hn::ScatterIndex(hn::BitCast(di, t_enter), di, out_ints, at + hn::Set(di, 1));
      hn::ScatterIndex(hn::BitCast(di, t_exit), di, out_ints, at + hn::Set(di, 2));
      found = found + hn::IfThenElseZero(keep, hn::Set(di, 1));

      // gr_dda_step: stop at t_end, else step the nearest boundary's axis (x, y, z on ties).
      Mask go = hn::AndNot(t_exit >= t_end, active);
      const Mask sel_x = hn::And(go, hn::And(x.tn <= y.tn, x.tn <= z.tn));
      const Mask sel_y = hn::And(hn::AndNot(sel_x, go), y.tn <= z.tn);
      const Mask sel_z = hn::AndNot(hn::Or(sel_x, sel_y), go);
      const Mask left_x = x.advance(sel_x);
      const Mask left_y = y.advance(sel_y);
      const Mask left_z = z.advance(sel_z);
      go = hn::AndNot(hn::Or(left_x, hn::Or(left_y, left_z)), go);
      t_enter = hn::IfThenElse(go, t_exit, t_enter);
      t_exit = hn::IfThenElse(go, exitOf(x, y, z, t_end, t_enter), t_exit);
      active = go;
    }
    alignas(64) int32_t found_of[kLanes];
    hn::Store(found, di, found_of);
    for (int k = 0; k < count; ++k) counts[k] = found_of[k];
  }
};

// Whether the target has a vector unit: Highway's EMU128 and SCALAR targets emulate the
// lanes in plain code, slower than the scalar walk.
constexpr bool kVectorUnit = HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR;

// The widest walk the target's vectors hold, at most kDdaPacketMaxLanes; without a vector
// unit, packets of kDdaPacketMaxLanes rays walked one after another.
constexpr int kWidest = !kVectorUnit             ? kDdaPacketMaxLanes
                        : HWY_LANES(float) >= 16 ? 16
                        : HWY_LANES(float) >= 8  ? 8
                        : HWY_LANES(float) >= 4  ? 4
                                                 : 1;
static_assert(kWidest <= kDdaPacketMaxLanes, "");

// The scalar walk of grid_dda.h, ray by ray, into the packet's layout.
void walkOneByOne(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
                  ListEntry* out, int stride, int* counts) {
  for (int k = 0; k < count; ++k) {
    const GrRay& ray = rays[k];
    ListEntry* list = out + size_t(k) * stride;
    int found = 0;
    GrDda s;
    if (gr_dda_begin(&g, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax, &s)) {
      do {
        const int pe = pe_of_voxel[s.ix + g.nx * (s.iy + g.ny * s.iz)];
        if (pe != -1) list[found++] = ListEntry{pe, s.t_enter, s.t_exit};
      } while (gr_dda_step(&g, &s));
    }
    counts[k] = found;
  }
}

// The walk of kLanes lanes where the target's vectors hold them; aborts elsewhere (callers
// check ddaPacketWidthIsBuilt).
template <size_t kLanes>
void walkIfBuilt(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
                 ListEntry* out, int stride, int* counts) {
  if constexpr (kLanes <= HWY_LANES(float)) {
    PacketWalk<kLanes>::run(g, pe_of_voxel, rays, count, out, stride, counts);
  } else {
    std::abort();
  }
}

}  // namespace

int ddaPacketLanes() { return kWidest; }

bool ddaPacketWidthIsBuilt(int lanes) {
  return (lanes == 1 || lanes == 4 || lanes == 8 || lanes == 16) &&
         size_t(lanes) <= HWY_LANES(float);
}

void ddaPacketOfWidth(int lanes, const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays,
                      int count, ListEntry* out, int stride, int* counts) {
  switch (lanes) {
    case 1:
      return walkIfBuilt<1>(g, pe_of_voxel, rays, count, out, stride, counts);
    case 4:
      return walkIfBuilt<4>(g, pe_of_voxel, rays, count, out, stride, counts);
    case 8:
      return walkIfBuilt<8>(g, pe_of_voxel, rays, count, out, stride, counts);
    case 16:
      return walkIfBuilt<16>(g, pe_of_voxel, rays, count, out, stride, counts);
    default:
      std::abort();  // callers check ddaPacketWidthIsBuilt
  }
}

void ddaPacket(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
               ListEntry* out, int stride, int* counts) {
  if constexpr (kVectorUnit)
    ddaPacketOfWidth(kWidest, g, pe_of_voxel, rays, count, out, stride, counts);
  else
    walkOneByOne(g, pe_of_voxel, rays, count, out, stride, counts);
}

}  // namespace gridrt
