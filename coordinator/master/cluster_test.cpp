// cluster_test.cpp - a slave is lost only by its own silence since it was last given work.
#include <gtest/gtest.h>

#include "cluster.h"

using namespace fc;

TEST(Cluster, ASlaveIsSilentOnlySinceItWasLastGivenWork)
{
    SlaveInfo s;
    s.last_msg = 10;        // its last result; then it waited, idle, for the others
    EXPECT_DOUBLE_EQ(s.silent_for(100), 90);
    s.last_given = 99;      // re-queued work of a lost slave reaches it
    EXPECT_DOUBLE_EQ(s.silent_for(100), 1);
    s.last_msg = 99.5;      // its heartbeat
    EXPECT_DOUBLE_EQ(s.silent_for(100), 0.5);
}
