/* 3D-DDA through a uniform grid (Amanatides & Woo 1987, "A Fast Voxel Traversal
 * Algorithm for Ray Tracing"), shared by the host (traversal lists) and the `dda` kernel.
 *
 * Robustness choices:
 *  - a zero direction component (+0.0 or -0.0) gets step 0 and an infinite boundary
 *    distance, set explicitly, so no 0*inf NaN is ever formed;
 *  - the distance to the next boundary plane of an axis is computed from the voxel index
 *    (min + k*cell) when the traversal steps along that axis, never accumulated, and
 *    consecutive voxels share the same boundary value exactly: every t of the ray belongs
 *    to a voxel interval, none falls between two;
 *  - when boundaries tie (the ray passes through an edge or a corner) one axis is stepped
 *    at a time, so the voxels in between appear with a zero-length interval;
 *  - a subnormal direction component is flushed to zero (its reciprocal would overflow to
 *    inf, and 0*inf at a boundary through the origin is NaN, which collapsed the walk);
 *    devices that flush denormals already see it as zero, so host and kernel agree;
 *  - a ray with a non-finite component misses the grid. */
#ifndef GRIDRT_GRID_DDA_H
#define GRIDRT_GRID_DDA_H
#include "gridrt_types.h"
#ifndef __OPENCL_C_VERSION__
#include <math.h>
#endif

#ifdef __OPENCL_C_VERSION__
#define GR_INF INFINITY
#define GR_ISFINITE(x) isfinite(x)
#else
#define GR_INF (__builtin_inff())
#define GR_ISFINITE(x) (__builtin_isfinite(x))
#endif
#define GR_FLT_MIN 1.17549435e-38f /* smallest normal float: 1/GR_FLT_MIN is finite */

typedef struct {
  int ix, iy, iz;        /* current voxel */
  int sx, sy, sz;        /* step per axis: -1, 0 or +1 */
  float t_enter, t_exit; /* the current voxel's interval along the ray */
  float t_end;           /* where the traversal stops: min(ray tmax, grid exit) */
  float ox, oy, oz;
  float idx, idy, idz; /* 1/direction, unused on a zero axis */
  float tnx, tny, tnz; /* distance to the current voxel's far boundary on each axis */
} GrDda;

GR_FN int gr_clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* Plane k of a grid axis, min + k * cell in float: the one arithmetic the walk, the PEs'
 * boxes and the host's binning all use, so they share every plane's float bit for bit. */
GR_FN float gr_grid_plane(float grid_min, float cell, int k) { return grid_min + (float)k * cell; }

/* An axis's step (-1, 0 or +1) and 1/direction, unused on a zero axis; a subnormal
 * component walks as 0 (see above). */
GR_FN void gr_axis_walk(float d, int* step, float* inv) {
  *step = d >= GR_FLT_MIN ? 1 : (d <= -GR_FLT_MIN ? -1 : 0);
  *inv = *step != 0 ? 1.0f / d : 0.0f;
}

/* Entry and exit of the slab [lo, hi] along one axis; returns 0 if the ray misses it. */
GR_FN int gr_slab(float o, float d, float lo, float hi, float* t0, float* t1) {
  if (d == 0.0f) {
    if (o < lo || o > hi) return 0;
    *t0 = -GR_INF;
    *t1 = GR_INF;
    return 1;
  }
  float inv = 1.0f / d;
  float a = (lo - o) * inv;
  float b = (hi - o) * inv;
  *t0 = a < b ? a : b;
  *t1 = a < b ? b : a;
  return 1;
}

/* Distance along the ray to the far boundary of voxel i on one axis. */
GR_FN float gr_next_boundary(float grid_min, float cell, int i, int step, float o, float inv) {
  if (step == 0) return GR_INF;
  int k = step > 0 ? i + 1 : i;
  return (gr_grid_plane(grid_min, cell, k) - o) * inv;
}

GR_FN void gr_dda_update_exit(GrDda* s) {
  float t = s->tnx < s->tny ? s->tnx : s->tny;
  t = t < s->tnz ? t : s->tnz;
  t = t < s->t_end ? t : s->t_end;
  s->t_exit = t > s->t_enter ? t : s->t_enter;
}

/* Starts a traversal of the ray (o, d) over [tmin, tmax]. Returns 0 if it misses the grid. */
GR_FN int gr_dda_begin(const GrGridInfo* g, float ox, float oy, float oz, float dx, float dy,
                       float dz, float tmin, float tmax, GrDda* s) {
  if (!(GR_ISFINITE(ox) && GR_ISFINITE(oy) && GR_ISFINITE(oz) && GR_ISFINITE(dx) &&
        GR_ISFINITE(dy) && GR_ISFINITE(dz)))
    return 0;
  if (dx > -GR_FLT_MIN && dx < GR_FLT_MIN) dx = 0.0f;
  if (dy > -GR_FLT_MIN && dy < GR_FLT_MIN) dy = 0.0f;
  if (dz > -GR_FLT_MIN && dz < GR_FLT_MIN) dz = 0.0f;
  float ax0, ax1, ay0, ay1, az0, az1;
  if (!gr_slab(ox, dx, g->minx, gr_grid_plane(g->minx, g->cellx, g->nx), &ax0, &ax1)) return 0;
  if (!gr_slab(oy, dy, g->miny, gr_grid_plane(g->miny, g->celly, g->ny), &ay0, &ay1)) return 0;
  if (!gr_slab(oz, dz, g->minz, gr_grid_plane(g->minz, g->cellz, g->nz), &az0, &az1)) return 0;
  float t0 = tmin;
  t0 = ax0 > t0 ? ax0 : t0;
  t0 = ay0 > t0 ? ay0 : t0;
  t0 = az0 > t0 ? az0 : t0;
  float t1 = tmax;
  t1 = ax1 < t1 ? ax1 : t1;
  t1 = ay1 < t1 ? ay1 : t1;
  t1 = az1 < t1 ? az1 : t1;
  if (!(t0 <= t1)) return 0;
  s->ox = ox;
  s->oy = oy;
  s->oz = oz;
  gr_axis_walk(dx, &s->sx, &s->idx);
  gr_axis_walk(dy, &s->sy, &s->idy);
  gr_axis_walk(dz, &s->sz, &s->idz);
  /* The entry voxel: where the ray is at t0, clamped into the grid against rounding. */
  float px = ox + t0 * dx, py = oy + t0 * dy, pz = oz + t0 * dz;
  s->ix = gr_clampi((int)floor((px - g->minx) / g->cellx), 0, g->nx - 1);
  s->iy = gr_clampi((int)floor((py - g->miny) / g->celly), 0, g->ny - 1);
  s->iz = gr_clampi((int)floor((pz - g->minz) / g->cellz), 0, g->nz - 1);
  s->t_enter = t0;
  s->t_end = t1;
  s->tnx = gr_next_boundary(g->minx, g->cellx, s->ix, s->sx, ox, s->idx);
  s->tny = gr_next_boundary(g->miny, g->celly, s->iy, s->sy, oy, s->idy);
  s->tnz = gr_next_boundary(g->minz, g->cellz, s->iz, s->sz, oz, s->idz);
  gr_dda_update_exit(s);
  return 1;
}

/* Moves to the next voxel along the ray. Returns 0 when the traversal is over. */
GR_FN int gr_dda_step(const GrGridInfo* g, GrDda* s) {
  if (s->t_exit >= s->t_end) return 0;
  /* Step exactly one axis: the nearest boundary, x before y before z on ties. */
  if (s->tnx <= s->tny && s->tnx <= s->tnz) {
    s->ix += s->sx;
    if (s->ix < 0 || s->ix >= g->nx) return 0;
    s->tnx = gr_next_boundary(g->minx, g->cellx, s->ix, s->sx, s->ox, s->idx);
  } else if (s->tny <= s->tnz) {
    s->iy += s->sy;
    if (s->iy < 0 || s->iy >= g->ny) return 0;
    s->tny = gr_next_boundary(g->miny, g->celly, s->iy, s->sy, s->oy, s->idy);
  } else {
    s->iz += s->sz;
    if (s->iz < 0 || s->iz >= g->nz) return 0;
    s->tnz = gr_next_boundary(g->minz, g->cellz, s->iz, s->sz, s->oz, s->idz);
  }
  s->t_enter = s->t_exit;
  gr_dda_update_exit(s);
  return 1;
}

#endif
