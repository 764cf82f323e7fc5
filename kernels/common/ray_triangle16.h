/* The 16-lane ray/triangle test of the kernels, chosen like ray_triangle.h. */
#ifndef GRIDRT_RAY_TRIANGLE16_H
#define GRIDRT_RAY_TRIANGLE16_H
#ifdef GR_WATERTIGHT
#include "watertight16.h"
#define gr_intersect16 gr_intersect_watertight16
#define gr_prepare_rays16 gr_wt_shear16
#else
#include "moller_trumbore16.h"
#define gr_intersect16 gr_intersect_mt16
/* Moeller-Trumbore needs nothing per packet. */
inline void gr_prepare_rays16(GrRays16* r) { (void)r; }
#endif
#endif
