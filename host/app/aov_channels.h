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

// The AOVs --aov-file holds without a bare --aov NAME: every one but the diagnostics.
inline constexpr const char* kLayerAovNames[] = {"depth", "primid", "normal", "geonormal",
                                                 "albedo"};

// The channels of AOV `name` (width * height pixels of the film), each name preceded by
// `prefix`. With an empty prefix, the AOV's own file (--aov NAME=FILE): 32-bit floats,
// "Y" (ids exact up to 2^24) or "R", "G", "B". As the layer "NAME." of --aov-file, in
// OpenEXR's names: depth "Z", primid and pe "id" as 32-bit unsigned integers (exact; a
// miss, -1, is 2^32 - 1), normal and geonormal "X", "Y", "Z", albedo "R", "G", "B", the
// counts tests and listlen "Y".
std::vector<ImageChannel> aovChannels(const PrimaryAovs& aovs, const std::string& name,
                                      const std::string& prefix);

// The value of a pixel nothing was traced for (outside a crop window): the miss value,
// -1 for depth and ids, else 0.
float aovMissValue(const std::string& name);

}  // namespace gridrt
