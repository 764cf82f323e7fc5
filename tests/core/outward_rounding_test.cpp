#include "outward_rounding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// floatBelow and floatAbove are the float neighbours of x on either side, as std::nextafter
// finds them: on zeros of both signs, denormals, the float range's ends, values past it,
// infinities, floats themselves and random doubles of every magnitude and sign.
TEST(OutwardRounding, IsTheNearestFloatOnEitherSide) {
  std::vector<double> xs = {0.0,
                            -0.0,
                            1e-320,
                            -1e-320,
                            1e-46,
                            -1e-46,
                            double(std::numeric_limits<float>::denorm_min()),
                            double(std::numeric_limits<float>::min()),
                            -double(std::numeric_limits<float>::min()),
                            double(std::numeric_limits<float>::max()),
                            -double(std::numeric_limits<float>::max()),
                            1e39,
                            -1e39,
                            double(kInf),
                            -double(kInf),
                            1.0,
                            -1.0,
                            1.0 + 0x1p-30,
                            -1.0 - 0x1p-30};
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-160, 140);
  for (int k = 0; k < 200000; ++k) xs.push_back(std::ldexp(mantissa(random), exponent(random)));
  for (double x : xs) {
    const float f = float(x);
    const float below = double(f) > x ? std::nextafter(f, -kInf) : f;
    const float above = double(f) < x ? std::nextafter(f, kInf) : f;
    ASSERT_EQ(floatBelow(x), below) << x;
    ASSERT_EQ(floatAbove(x), above) << x;
    ASSERT_EQ(std::signbit(floatBelow(x)), std::signbit(below)) << x;
    ASSERT_EQ(std::signbit(floatAbove(x)), std::signbit(above)) << x;
    ASSERT_LE(double(floatBelow(x)), x);
    ASSERT_GE(double(floatAbove(x)), x);
  }
  EXPECT_TRUE(std::isnan(floatBelow(std::nan(""))));
  EXPECT_TRUE(std::isnan(floatAbove(std::nan(""))));
}

}  // namespace
}  // namespace gridrt
