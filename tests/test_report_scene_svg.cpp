// placeholder while building
#include <gtest/gtest.h>
TEST(SceneSvg, Placeholder) {}
