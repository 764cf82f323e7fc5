#include "frame_statistics.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "errors.h"

namespace gridrt {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void FramePhaseTimes::add(const FrameTimes& times) {
  frame_ms.push_back(times.frame_ms);
  shade_ms.push_back(times.shade_ms);
  intersect_ms.push_back(times.intersectMs());
  primary_ms.push_back(times.primary_ms);
  secondary_ms.push_back(times.secondary_ms);
  shadow_ms.push_back(times.shadow_ms);
}

void FramePhaseTimes::append(const FramePhaseTimes& other) {
  auto join = [](std::vector<double>& to, const std::vector<double>& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  join(frame_ms, other.frame_ms);
  join(shade_ms, other.shade_ms);
  join(intersect_ms, other.intersect_ms);
  join(primary_ms, other.primary_ms);
  join(secondary_ms, other.secondary_ms);
  join(shadow_ms, other.shadow_ms);
}

nlohmann::json frameStatistics(const FramePhaseTimes& phases, const RayCounts& rays) {
  auto perRay = [](double ms, uint64_t count) { return count ? ms * 1e6 / double(count) : 0.0; };
  const double frame_ms = median(phases.frame_ms), primary_ms = median(phases.primary_ms),
               secondary_ms = median(phases.secondary_ms), shadow_ms = median(phases.shadow_ms);
  nlohmann::json stats;
  stats["frame_ms"] = frame_ms;
  stats["mrays_per_s"] = frame_ms > 0 ? rays.total() / (frame_ms * 1e3) : 0.0;
  stats["shade_ms"] = median(phases.shade_ms);
  stats["intersect_ms"] = median(phases.intersect_ms);
  stats["trace"] = {
      {"primary_ms", primary_ms},
      {"secondary_ms", secondary_ms},
      {"shadow_ms", shadow_ms},
      {"primary_ns_per_ray", perRay(primary_ms, rays.primary)},
      {"secondary_ns_per_ray", perRay(secondary_ms, rays.reflection + rays.refraction)},
      {"shadow_ns_per_ray", perRay(shadow_ms, rays.shadow)}};
  return stats;
}

namespace {
void flatten(const nlohmann::json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& rows) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      flatten(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), rows);
    return;
  }
  std::string value;
  if (j.is_number_float()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g", j.get<double>());
    value = buf;
  } else if (j.is_string()) {
    value = j.get<std::string>();
  } else {
    value = j.dump();
  }
  rows.emplace_back(prefix, value);
}
}  // namespace

std::string formatStatisticsTable(const nlohmann::json& stats) {
  std::vector<std::pair<std::string, std::string>> rows;
  flatten(stats, "", rows);
  size_t width = 0;
  for (const auto& r : rows) width = std::max(width, r.first.size());
  std::ostringstream os;
  for (const auto& r : rows)
    os << r.first << std::string(width + 2 - r.first.size(), ' ') << r.second << '\n';
  return os.str();
}

void writeJsonFile(const std::string& path, const nlohmann::json& stats) {
  if (path == kStandardOutput) {
    std::cout << stats.dump(2) << '\n' << std::flush;
    if (!std::cout) throw RenderError("cannot write the statistics to standard output");
    return;
  }
  std::string temp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temp);
    out << stats.dump(2) << '\n';
    if (!out) {
      std::remove(temp.c_str());
      throw RenderError("cannot write '" + path + "'");
    }
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    throw RenderError("cannot write '" + path + "'");
  }
}

}  // namespace gridrt
