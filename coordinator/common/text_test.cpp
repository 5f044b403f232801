// text_test.cpp - the string helpers.
#include <gtest/gtest.h>

#include "text.h"

using namespace fc;

TEST(Text, StrfFormatsLongStringsWhole)
{
    std::string long_one(2000, 'x');
    EXPECT_EQ(strf("%s!", long_one.c_str()), long_one + "!");
    EXPECT_EQ(strf("%d-%s", 7, "a"), "7-a");
}

TEST(Text, TrimPrefixSuffixAndSizes)
{
    EXPECT_EQ(trim(" \t a b \t"), "a b");
    EXPECT_EQ(trim("   "), "");
    EXPECT_TRUE(starts_with("fc-master", "fc-"));
    EXPECT_FALSE(starts_with("fc", "fc-"));
    EXPECT_TRUE(ends_with("clk01.png", ".png"));
    EXPECT_FALSE(ends_with("png", ".png"));
    EXPECT_EQ(human_bytes(512), "512 bytes");
    EXPECT_EQ(human_bytes(230 * 1024.0), "230 KB");
    EXPECT_EQ(human_bytes(10.4 * 1024 * 1024), "10.4 MB");
}
