#include "oblique/status.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "oblique/depth_convention.h"
#include "oblique/oblique.h"

namespace oblique {
namespace {

TEST(Status, codesAreDistinctAndParseBack) {
  std::set<std::string_view> codes, messages;
  for (Status s : all_statuses) {
    EXPECT_EQ(parse_status(status_code(s)), s);
    codes.insert(status_code(s));
    messages.insert(status_message(s));
  }
  EXPECT_EQ(codes.size(), std::size(all_statuses));
  EXPECT_EQ(messages.size(), std::size(all_statuses));
  EXPECT_FALSE(parse_status("OK"));
}

TEST(Status, conventionsAndMethodsParseBack) {
  for (Convention c : all_conventions) EXPECT_EQ(parse_convention(convention_name(c)), c);
  for (Method m : all_methods) EXPECT_EQ(parse_method(method_name(m)), m);
  EXPECT_FALSE(parse_convention("d3d"));
  EXPECT_EQ(parse_method("auto"), Method::automatic);
}

}  // namespace
}  // namespace oblique
