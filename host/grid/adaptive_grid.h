// The adaptive structure of GridRT: a grid that models no more than the scene needs, with
// the architecture unchanged (its leaves are the PEs, each with its own box and triangles;
// rays meet them in order along the ray, docs/adaptive-grid.md).
//
// - The top level is the uniform grid of the automatic resolution (uniform_grid.h).
// - A cell holding more than kMaxLeafTriangles triangles gets a grid of its own, its
//   resolution from its own triangle count and shape: the one at which a surface crossing
//   the cell leaves about kSurfaceCellShare of the limit in each cell it passes through,
//   recursively up to kMaxAdaptiveDepth levels below the top (the two-level grid of
//   Kalojanov, Billeter and Slusallek 2011, made multi-level for a model small in a large
//   cell, the "teapot in a stadium").
// - Neighbouring top cells that are leaves merge into one leaf whose box is their union
//   (the merging step of Perard-Gayot, Kalojanov and Slusallek's irregular grids, 2017),
//   greedily along x, then y, then z, while the merged leaf holds the same triangles as
//   each of its cells or at most kMergeMaxTriangles (a floor, a huge triangle, a wall:
//   their cells hold one or both of a quad's two triangles).
// A triangle is listed in a leaf when it overlaps the leaf's box grown by the grid's
// margin (exact separating-axis test), as in the uniform grid. A leaf's faces are planes of
// the grids above it, stored once as floats, so two leaves sharing a face share its float
// and its distance along every ray bit for bit.
#pragma once
#include <vector>

#include "uniform_grid.h"

namespace gridrt {

// A leaf holding more triangles than this is split (when its grid would have more than
// one cell): GridSettings::max_leaf_triangles' default. Measured (docs/adaptive-grid.md):
// above the fullest voxel of the full bunny's auto grid (179), so the even scenes keep
// their grid.
constexpr int kMaxLeafTriangles = 256;
static_assert(GridSettings{}.max_leaf_triangles == kMaxLeafTriangles, "one default");
// A grid below a full cell aims at this share of the leaf limit in each cell a surface
// crosses: half, so a cell the estimate puts a little over is rarely split again, and one
// it puts under is far from the limit. Measured on the uneven scenes (camera rays and
// build, docs/adaptive-grid.md): a quarter split the floor 100x its size into 4,010 PEs
// (the volume rule 1,382, a half 2,000) and traced no faster; with a half the scattered
// copies' build took 123 -> 82 ms and their camera rays 7.1 -> 5.7.
constexpr double kSurfaceCellShare = 0.5;
// Merged top leaves hold at most this many triangles (unless every cell holds the same).
constexpr int kMergeMaxTriangles = 8;
// Levels of grids below the top grid at most.
constexpr int kMaxAdaptiveDepth = 3;
// A grid below a cell has no cell narrower than this many grid margins on any axis. Every
// leaf lists the triangles within a margin of its box, so once cells near the margin a
// finer grid no longer thins its leaves, it only adds PEs (the bunny on a floor 1000 times
// its size, margin 3 mm: its 8 mm cells held 112 triangles each over 13,892 PEs; with
// cells of 4 margins or more, 141 over 1,750, and its camera rays trace in half the time).
constexpr double kMinCellMargins = 4.0;

// Builds the adaptive structure over `triangles` (global order); settings as for
// buildUniformGrid (automatic resolution for the top grid). Runs on all cores.
UniformGrid buildAdaptiveGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                              const GridSettings& settings);

// The same over a top grid binned already (the uniform grid of the automatic resolution).
UniformGrid adaptiveGridOver(const UniformBins& top, const std::vector<GrTriangle>& triangles,
                             const GridSettings& settings);

// The grid the settings ask for (GridSettings::structure; a fixed resolution is uniform).
// WhereNeeded keeps the uniform grid when no voxel holds more than max_leaf_triangles: its
// voxels already fit the scene (docs/adaptive-grid.md, "Default").
UniformGrid buildGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                      const GridSettings& settings);

}  // namespace gridrt
