// Every key the viewer answers to is documented, and none does two things.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "key_bindings.h"
#include "test_support.h"

namespace gridrt {
namespace {

TEST(KeyBindings, DocsViewerMdNamesEveryKey) {
  std::ifstream in(test::sourcePath("docs/viewer.md"));
  ASSERT_TRUE(in) << "docs/viewer.md is missing";
  std::stringstream text;
  text << in.rdbuf();
  for (const KeyBinding& b : keyBindings())
    EXPECT_NE(text.str().find("| " + std::string(b.label)), std::string::npos)
        << b.label << " is not in docs/viewer.md's table of keys";
}

TEST(KeyBindings, EachKeyDoesOneThing) {
  std::set<int> keys;
  for (const KeyBinding& b : keyBindings()) EXPECT_TRUE(keys.insert(b.key).second) << b.label;
  ViewAction action;
  EXPECT_TRUE(actionOfKey('p', action));
  EXPECT_EQ(action, ViewAction::Snapshot);
  EXPECT_FALSE(actionOfKey('z', action));
}

}  // namespace
}  // namespace gridrt
