#include <gtest/gtest.h>
TEST(ViewCamera, Placeholder) {}
