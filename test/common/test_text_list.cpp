// A list given as one piece of text (common/text_list.hpp): the items between the separators, empty ones left out.
#include <gtest/gtest.h>

#include "cosmo/common/text_list.hpp"

using cosmo::splitList;

TEST(TextList, ItemsBetweenTheSeparatorsWithoutEmptyOnes) {
  EXPECT_EQ(splitList("wifi,proradio"), (std::vector<std::string>{"wifi", "proradio"}));
  EXPECT_EQ(splitList(",a,,b,"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(splitList("32;64", ';'), (std::vector<std::string>{"32", "64"}));
  EXPECT_TRUE(splitList("").empty());
}
