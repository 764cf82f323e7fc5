// The AOVs --aov writes: their names, their channels in a file and their miss values.
#pragma once
#include <string>
#include <vector>

#include "layered_image.h"

namespace gridrt {

struct PrimaryAovs;

inline constexpr const char* kAovNames[] = {"depth",  "primid", "normal", "geonormal",
                                            "albedo", "tests",  "pe",     "listlen"};

inline bool isAovName(const std::string& name) {
  for (const char* known : kAovNames)
    if (name == known) return true;
  return false;
}
// The AOVs of the intersector's counters (RenderSettings::want_diagnostics): tests, pe,
// listlen.
inline bool isDiagnosticAov(const std::string& name) {
  return name == "tests" || name == "pe" || name == "listlen";
}

// The channels of AOV `name` (width * height pixels of the film), each name preceded by
// `prefix` (empty in the AOV's own file).
std::vector<ImageChannel> aovChannels(const PrimaryAovs& aovs, const std::string& name,
                                      const std::string& prefix);

// The value of a pixel nothing was traced for (outside a crop window): the miss value,
// -1 for depth and ids, else 0.
float aovMissValue(const std::string& name);

}  // namespace gridrt
