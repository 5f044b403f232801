// Tests for UnitIds: ids kept by unchanged units from frame to frame.
#include <gtest/gtest.h>

#include <vector>

#include "povrayfc/unit_ids.h"

namespace povrayfc {
namespace {

TEST(UnitIds, UnchangedUnitsKeepTheirIdsAndFreedIdsWaitAFrame) {
    UnitIds ids;
    ids.Reset(3);
    EXPECT_EQ(ids.Current(), (std::vector<std::uint32_t>{0, 1, 2}));
    std::vector<std::uint32_t> changed;
    // Unit 1 of the last frame vanished; the new frame has the old units 0 and 2 (in
    // another order) and a new one.
    ids.Advance({2, UnitIds::kNone, 0}, {1}, changed);
    EXPECT_EQ(changed, std::vector<std::uint32_t>{1});
    // Invariant: id 1 is still referred to by samples traced again only this frame: the new
    // unit gets a fresh id.
    EXPECT_EQ(ids.Current()[0], 2u);
    EXPECT_EQ(ids.Current()[2], 0u);
    EXPECT_EQ(ids.Current()[1], 3u);
    changed.clear();
    ids.Advance({0, 1, 2, UnitIds::kNone}, {}, changed);
    EXPECT_TRUE(changed.empty());
    EXPECT_EQ(ids.Current()[3], 1u);   // now it may be given out again
    EXPECT_EQ(ids.Limit(), 4u);
}

}  // namespace
}  // namespace povrayfc
