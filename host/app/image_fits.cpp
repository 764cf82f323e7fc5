#include "image_fits.h"

#include <unistd.h>

#include <string>

#include "errors.h"
#include "memory_estimate.h"

namespace gridrt {

namespace {

[[noreturn]] void refuseImage(const Options& o, double bytes, double limit_bytes,
                              const char* where) {
  const std::string window =
      o.crop ? " (window " + std::to_string(o.crop->x0) + "," + std::to_string(o.crop->y0) + "," +
                   std::to_string(o.crop->x1) + "," + std::to_string(o.crop->y1) +
                   (o.crop_output == CropOutput::Full ? ", written full size)" : ")")
             : "";
  throw RenderError("image " + std::to_string(o.width) + "x" + std::to_string(o.height) + window +
                    " at " + std::to_string(o.spp) + " spp needs about " +
                    std::to_string((long long)(bytes / (1 << 20))) + " MiB, more than the " +
                    std::to_string((long long)(limit_bytes / (1 << 20))) + " MiB of " + where);
}

MemoryEstimate estimateOf(const Options& o) {
  return estimateMemory(o.width, o.height, o.spp, o.crop ? *o.crop : PixelWindow{},
                        o.crop_output == CropOutput::Full,
                        o.accel == AccelKind::GridRt && o.transfer == BatchTransfer::Copy);
}

}  // namespace

void checkImageFitsHost(const Options& o) {
  const double host = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  const double need = estimateOf(o).host_bytes;
  if (need > host) refuseImage(o, need, host, "host memory");
}

void checkImageFitsDevice(const Options& o, const DeviceInfo& device) {
  const double need = estimateOf(o).device_bytes;
  if (need > double(device.global_mem_bytes))
    refuseImage(o, need, double(device.global_mem_bytes), "device memory");
}

}  // namespace gridrt
