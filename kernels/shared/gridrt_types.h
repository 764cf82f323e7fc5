/* Struct layouts shared by the host (C++) and the kernels (OpenCL C 1.2).
 * One truth: the host includes this file and pins every layout with static_assert
 * (host/shared_layout.h). No float3 (16 bytes in OpenCL C): scalars only. */
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

/* A triangle prepared for the intersectors: first vertex and the two edges from it
 * (Moeller-Trumbore). In the watertight build the e fields hold the vertices v1 and v2
 * themselves: v0 + e1 in float does not always give back v1, and neighbours must share
 * their edge vertices bit for bit to be watertight. */
typedef struct {
  float v0x, v0y, v0z;
  float e1x, e1y, e1z;
  float e2x, e2y, e2z;
  int prim;          /* global triangle index in load order */
  int vertex_layout; /* 1: e1/e2 hold v1/v2 (watertight build), 0: edges */
  int pad1;
} GrTriangle; /* 48 bytes */

/* The closest hit found for one ray (or one ray inside one PE): prim < 0 means none. */
typedef struct {
  float t;
  int prim;
  float u, v; /* barycentrics of vertices 1 and 2 */
} GrHit; /* 16 bytes */

/* The uniform grid as the kernels see it. */
typedef struct {
  float minx, miny, minz, pad0;
  float cellx, celly, cellz, pad1; /* voxel size per axis */
  int nx, ny, nz, pe_count;
} GrGridInfo; /* 48 bytes */

/* One (ray, PE) pair produced by the traversal lists and binned per PE. */
typedef struct {
  int ray;       /* index of the ray in the batch */
  int slot;      /* index of this pair in the ray-major traversal list (result slot) */
  float t_enter; /* ray parameter where the ray enters the PE's voxel */
  float t_exit;  /* ... and where it leaves it */
} GrPeEntry; /* 16 bytes */

/* One work-group's share of one PE: entries [first_entry, first_entry + entry_count);
 * an entry's result goes to slot_base + entry.slot. */
typedef struct {
  int pe;
  int first_entry;
  int entry_count;
  int slot_base;
} GrPeTask; /* 16 bytes */

#endif
