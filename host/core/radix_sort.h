// Sorting (float key, int) pairs by key in linear time: a least-significant-digit radix
// sort over the keys' bits, stable, so pairs of equal keys keep their input order. Pairs
// whose ints increase in input order come out as std::sort of the pairs would put them
// (by key, then by int), but for -0 and +0, which it orders -0 first, and NaNs, which it
// puts at the ends (std::sort's order is undefined with them).
#pragma once
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace gridrt {

// The float's bits as an unsigned integer in the same order as the floats: negative
// numbers with every bit flipped, the others with the sign bit set.
inline uint32_t orderedFloatBits(float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

// Sorts `items` by their float keys (stable); `scratch` is memory reused between calls.
inline void radixSortByKey(std::vector<std::pair<float, int>>& items,
                           std::vector<std::pair<float, int>>& scratch) {
  // Three passes of 11 bits: the 32 bits of the key, 2,048 counters a pass.
  constexpr int kDigitBits = 11, kPasses = 3;
  constexpr uint32_t kDigits = 1u << kDigitBits;
  const size_t n = items.size();
  if (n < 2) return;
  scratch.resize(n);
  std::vector<uint32_t> count(size_t(kPasses) * kDigits, 0);
  for (const auto& item : items) {
    const uint32_t key = orderedFloatBits(item.first);
    for (int p = 0; p < kPasses; ++p)
      ++count[p * kDigits + ((key >> (p * kDigitBits)) & (kDigits - 1))];
  }
  std::vector<std::pair<float, int>>*from = &items, *to = &scratch;
  for (int p = 0; p < kPasses; ++p) {
    uint32_t* c = &count[size_t(p) * kDigits];
    if (c[(orderedFloatBits((*from)[0].first) >> (p * kDigitBits)) & (kDigits - 1)] == n)
      continue;  // every key has the same digit here: the pass would copy the order as it is
    uint32_t sum = 0;
    for (uint32_t d = 0; d < kDigits; ++d) {
      const uint32_t here = c[d];
      c[d] = sum;
      sum += here;
    }
    for (const auto& item : *from)
      (*to)[c[(orderedFloatBits(item.first) >> (p * kDigitBits)) & (kDigits - 1)]++] = item;
    std::swap(from, to);
  }
  if (from != &items) items.swap(scratch);
}

}  // namespace gridrt
