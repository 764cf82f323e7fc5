/* Classic uniform-grid traversal (the paper's Fig. 1): one work-item per ray walks the
 * grid with the shared 3D-DDA and stops at the first voxel holding a hit inside it. */
#pragma OPENCL FP_CONTRACT OFF
#include "grid_dda.h"
#include "gridrt_types.h"
#include "ray_triangle.h"

__kernel void dda_intersect(__global const GrRay* rays, int ray_count, GrGridInfo grid,
                            __global const int* pe_of_voxel, __global const int* pe_tri_begin,
                            __global const GrTriangle* pe_tris, int any_hit, __global GrHit* hits,
                            __global int* tests) {
  int id = get_global_id(0);
  if (id >= ray_count) return;
  GrRay ray = rays[id];
  GrHit best;
  best.t = ray.tmax;
  best.prim = -1;
  best.u = 0.0f;
  best.v = 0.0f;
  int count = 0;
  GrDda s;
  if (gr_dda_begin(&grid, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax, &s)) {
    do {
      int pe = pe_of_voxel[s.ix + grid.nx * (s.iy + grid.ny * s.iz)];
      if (pe < 0) continue;
      int end = pe_tri_begin[pe + 1];
      for (int i = pe_tri_begin[pe]; i < end; ++i) {
        GrTriangle tri = pe_tris[i];
        float t, u, v;
        ++count;
        if (gr_intersect(ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, tri.v0x, tri.v0y, tri.v0z,
                         tri.e1x, tri.e1y, tri.e1z, tri.e2x, tri.e2y, tri.e2z, &t, &u, &v) &&
            t > ray.tmin && t < best.t && t >= s.t_enter && t <= s.t_exit) {
          best.t = t;
          best.prim = tri.prim;
          best.u = u;
          best.v = v;
          if (any_hit) break;
        }
      }
      if (best.prim >= 0) break; /* early exit: no later voxel can be closer */
    } while (gr_dda_step(&grid, &s));
  }
  hits[id] = best;
  tests[id] = count;
}
