#include "aov_channels.h"

#include "renderer.h"

namespace gridrt {

std::vector<ImageChannel> aovChannels(const PrimaryAovs& aovs, const std::string& name,
                                      const std::string& prefix) {
  const bool layer = !prefix.empty();
  if (name == "primid" || name == "pe") {
    const std::vector<int32_t>& ids = name == "primid" ? aovs.primid : aovs.pe;
    if (layer) return {idChannel(prefix + "id", ids)};
    return {floatChannel(prefix + "Y", std::vector<float>(ids.begin(), ids.end()), 1, 0)};
  }
  const bool three = name == "normal" || name == "geonormal" || name == "albedo";
  const std::vector<float>& data = name == "depth"       ? aovs.depth
                                   : name == "normal"    ? aovs.shading_normal
                                   : name == "geonormal" ? aovs.normal
                                   : name == "albedo"    ? aovs.albedo
                                   : name == "tests"     ? aovs.tests
                                                         : aovs.list_length;
  if (!three) return {floatChannel(prefix + (layer && name == "depth" ? "Z" : "Y"), data, 1, 0)};
  const char* names = layer && name != "albedo" ? "XYZ" : "RGB";
  std::vector<ImageChannel> channels;
  for (int c = 0; c < 3; ++c)
    channels.push_back(floatChannel(prefix + std::string(1, names[c]), data, 3, c));
  return channels;
}

float aovMissValue(const std::string& name) {
  return name == "primid" || name == "pe" || name == "depth" ? -1.0f : 0.0f;
}

}  // namespace gridrt
