// Statistics of a run (--stats, --stats-json): per-phase times as medians over the
// repeated frames, ray counts, and the grid/PE figures of the GridRT architecture.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer.h"
#include "standard_streams.h"

namespace gridrt {

double median(std::vector<double> values);

// Summary of a list of counts: mean and max.
struct MeanMax {
  double mean = 0;
  double max = 0;
};
template <typename T>
MeanMax meanMax(const std::vector<T>& values) {
  MeanMax m;
  for (const auto& v : values) {
    m.mean += double(v);
    m.max = std::max(m.max, double(v));
  }
  if (!values.empty()) m.mean /= double(values.size());
  return m;
}

// The phases of the timed frames, one entry a frame (the warm-up frame left out).
struct FramePhaseTimes {
  std::vector<double> frame_ms, shade_ms, intersect_ms, primary_ms, secondary_ms, shadow_ms;
  void add(const FrameTimes& times);
  void append(const FramePhaseTimes& other);  // other's frames after these
};

// The figures of a run's frames as gridrt's statistics and the Embree peer's name them,
// built here only: the medians of frame_ms, shade_ms and intersect_ms, mrays_per_s, and
// "trace" (tracing time by ray kind and what a ray of each kind cost).
nlohmann::json frameStatistics(const FramePhaseTimes& phases, const RayCounts& rays);

// A readable two-column table of the JSON statistics (nested keys joined by '.').
std::string formatStatisticsTable(const nlohmann::json& stats);

// Writes `stats` to `path` atomically (a temporary file renamed), or to standard output.
void writeJsonFile(const std::string& path, const nlohmann::json& stats);

}  // namespace gridrt
