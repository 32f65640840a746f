#include <gtest/gtest.h>

#include "kaboum/core/error.hpp"

TEST(Locate, NamesFileLineAndColumn) {
  EXPECT_EQ(kaboum::locate("a.obj", "bad face", 12, 3), "a.obj:12:3: bad face");
  EXPECT_EQ(kaboum::locate("a.obj", "bad face", 12), "a.obj:12: bad face");
  EXPECT_EQ(kaboum::locate("a.obj", "empty mesh"), "a.obj: empty mesh");
}
