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

TEST(Cluster, AStalledSlavesCoresGoToTheOthersOfItsHost)
{
    Cluster c;
    c.hosts()[1].cpus = 4;
    c.hosts()[2].cpus = 2;
    for (int tid : {10, 11})
        c.slaves()[tid].dtid = 1;
    for (int tid : {20, 21})
        c.slaves()[tid].dtid = 2;
    for (auto &kv : c.slaves()) {
        kv.second.tid = kv.first;
        kv.second.state = SlaveState::Ready;
    }
    EXPECT_EQ(c.threads_for(c.slaves()[10], {}), 2);
    EXPECT_EQ(c.threads_for(c.slaves()[20], {}), 1);
    // Slave 11 is stopped: 10 renders with the host's four cores; another host's stall
    // changes nothing on host 1, and a stalled slave is never counted out of its own share.
    EXPECT_EQ(c.threads_for(c.slaves()[10], {11}), 4);
    EXPECT_EQ(c.threads_for(c.slaves()[10], {21}), 2);
    EXPECT_EQ(c.threads_for(c.slaves()[11], {11}), 2);
    // A slave that is gone leaves its cores too.
    c.slaves()[21].state = SlaveState::Gone;
    EXPECT_EQ(c.threads_for(c.slaves()[20], {}), 2);
}
