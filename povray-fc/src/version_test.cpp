#include <cstring>
#include <gtest/gtest.h>
#include "povrayfc/version.h"

// The header's version and the library's must agree, or the binary lies in --version.
TEST(Version, LibraryMatchesHeader) {
    EXPECT_STREQ(povrayfc::LibraryVersion(), POVRAYFC_VERSION);
    EXPECT_GT(std::strlen(POVRAYFC_VERSION), 0u);
}
