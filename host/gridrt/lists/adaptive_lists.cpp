#include "adaptive_lists.h"

#include <algorithm>

#include "grid_dda.h"

namespace gridrt {

namespace {

struct Walk {
  const UniformGrid& grid;
  std::vector<ListEntry>& out;
  size_t first;  // the ray's first entry in out
  float o[3], d[3], inv[3];
  int step[3];

  // A leaf from t_enter to t_exit: joins the previous entry when that is the same PE
  // ending where this begins (a merged leaf met in its next cell).
  void emit(int pe, float t_enter, float t_exit) {
    if (out.size() > first && out.back().pe == pe && out.back().t_exit == t_enter) {
      out.back().t_exit = t_exit;
      return;
    }
    // Field by field: a braced temporary was built on the stack with a 4- and an 8-byte
    // store and copied out with one 8-byte load, a store-forwarding stall that took a
    // third of the expansion's samples (perf, default Whitted frame).
    ListEntry& entry = out.emplace_back();
    entry.pe = pe;
    entry.t_enter = t_enter;
    entry.t_exit = t_exit;
  }

  // The walk of `ray` appending to `out`, with gr_dda_begin's steps and inverse directions.
  static Walk of(const UniformGrid& grid, const GrRay& ray, std::vector<ListEntry>& out) {
    Walk w{grid, out, out.size(), {ray.ox, ray.oy, ray.oz}, {ray.dx, ray.dy, ray.dz}, {}, {}};
    for (int a = 0; a < 3; ++a) gr_axis_walk(w.d[a], &w.step[a], &w.inv[a]);
    return w;
  }

  void cell(int code, float t_enter, float t_exit) {
    if (code >= 0)
      emit(code, t_enter, t_exit);
    else if (code <= -2)
      node(-(code + 2), t_enter, t_exit);
  }

  // The cells of grid node `n` from t0 to t1 (the interval of its cell above). The node
  // and the walk's values are copied into locals: the entries' stores could alias the
  // fields of references, which the compiler would then load again after every entry.
  void node(int n, float t0, float t1) {
    const GridNode g = grid.adaptive.nodes[n];
    const int* const cells = grid.adaptive.cells.data() + g.cell_begin;
    const float* p[3];
    int i[3];
    float tn[3];
    const float oo[3] = {o[0], o[1], o[2]}, ii[3] = {inv[0], inv[1], inv[2]};
    const int ss[3] = {step[0], step[1], step[2]};
    // The distance to the next plane along axis a.
    auto nextOf = [&](int a) {
      return ss[a] != 0 ? (p[a][ss[a] > 0 ? i[a] + 1 : i[a]] - oo[a]) * ii[a] : GR_INF;
    };
    for (int a = 0; a < 3; ++a) {
      p[a] = grid.adaptive.planes.data() + g.plane_begin[a];
      // The entry cell: where the ray is at t0 among the inner planes, clamped.
      const float x = ss[a] != 0 ? oo[a] + t0 * d[a] : oo[a];
      i[a] = int(std::upper_bound(p[a] + 1, p[a] + g.dims[a], x) - (p[a] + 1));
      tn[a] = nextOf(a);
    }
    const size_t before = out.size();
    float t_enter = t0, t_exit = t0;
    for (;;) {
      t_exit = std::min(std::min(tn[0], tn[1]), std::min(tn[2], t1));
      t_exit = std::max(t_exit, t_enter);
      cell(cells[i[0] + g.dims[0] * (i[1] + g.dims[1] * i[2])], t_enter, t_exit);
      if (t_exit >= t1) break;
      // One axis at a time, x before y before z on ties (as the 3D-DDA).
      const int a = tn[0] <= tn[1] && tn[0] <= tn[2] ? 0 : tn[1] <= tn[2] ? 1 : 2;
      i[a] += ss[a];
      if (i[a] < 0 || i[a] >= g.dims[a]) break;
      tn[a] = nextOf(a);
      t_enter = t_exit;
    }
    // Left the node before t1 (its entry cell found a rounding off): the last cell covers
    // the rest of the interval, so no distance of the ray falls between two entries.
    if (t_exit < t1 && out.size() > before && out.back().t_exit == t_exit) out.back().t_exit = t1;
  }
};

}  // namespace

void adaptiveList(const UniformGrid& grid, const GrRay& ray, std::vector<ListEntry>& out) {
  const GrGridInfo& g = grid.info;
  GrDda s;
  if (!gr_dda_begin(&g, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax, &s))
    return;
  Walk w = Walk::of(grid, ray, out);
  do {
    w.cell(grid.adaptive.top[s.ix + g.nx * (s.iy + g.ny * s.iz)], s.t_enter, s.t_exit);
  } while (gr_dda_step(&g, &s));
}

// The top grid is walked a packet of rays at a time (computeListsOverCells: the scalar
// walk's distances bit for bit), keeping the cells with a leaf or a grid below them; each
// ray's cells are then expanded as adaptiveList's walk does.
void computeAdaptiveLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                          TraversalLists& lists) {
  computeListsOverCells(
      grid.info, grid.adaptive.top.data(), rays, count, lists,
      [&grid](const GrRay& ray, const ListEntry* cells, int n, std::vector<ListEntry>& out) {
        Walk w = Walk::of(grid, ray, out);
        for (int c = 0; c < n; ++c) w.cell(cells[c].pe, cells[c].t_enter, cells[c].t_exit);
      });
}

}  // namespace gridrt
