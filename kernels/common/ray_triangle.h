/* The ray/triangle test every intersector uses, chosen at build time: Moeller-Trumbore
 * by default, the watertight test of Woop, Benthin & Wald (2013) with -DGR_WATERTIGHT.
 * Both have the signature of gr_intersect_mt (moller_trumbore.h). */
#ifndef GRIDRT_RAY_TRIANGLE_H
#define GRIDRT_RAY_TRIANGLE_H
#ifdef GR_WATERTIGHT
#include "watertight.h"
#define gr_intersect gr_intersect_watertight
#else
#include "moller_trumbore.h"
#define gr_intersect gr_intersect_mt
#endif
#endif
