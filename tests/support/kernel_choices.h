// The four ways GridRT's PE kernels can run on one device, for tests parameterised over
// them: both layouts of a work-group's rays (PeLayout: Packets, Lanes) with both batch
// transfers (BatchTransfer: Map, Copy). Every layout and transfer must give the same hits.
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "intersector.h"

namespace gridrt::test {

struct KernelChoice {
  PeLayout layout;
  BatchTransfer transfer;

  KernelOptions options(bool watertight = false) const {
    KernelOptions o;
    o.watertight = watertight;
    o.pe_layout = layout;
    o.transfer = transfer;
    return o;
  }
};

inline auto kernelChoices() {
  return ::testing::Values(KernelChoice{PeLayout::Packets, BatchTransfer::Map},
                           KernelChoice{PeLayout::Packets, BatchTransfer::Copy},
                           KernelChoice{PeLayout::Lanes, BatchTransfer::Map},
                           KernelChoice{PeLayout::Lanes, BatchTransfer::Copy});
}

// The parameter's name in the test's: PacketsMap, LanesCopy, ...
inline std::string kernelChoiceName(const ::testing::TestParamInfo<KernelChoice>& info) {
  return std::string(info.param.layout == PeLayout::Lanes ? "Lanes" : "Packets") +
         (info.param.transfer == BatchTransfer::Copy ? "Copy" : "Map");
}

}  // namespace gridrt::test
