// child_process_test.cpp - children whose output is read line by line, waited for with a
// bound, and killed with their process group.
#include <sys/wait.h>

#include <gtest/gtest.h>

#include "child_process.h"

using namespace fc;

TEST(ChildProcess, LinesOfBothStreamsAndTheExitStatus)
{
    Child c;
    std::string err;
    ASSERT_TRUE(start_child({"/bin/sh", "-c", "echo one; printf 'two\\rthree' >&2; exit 3"}, "",
                            0, c, err))
        << err;
    std::vector<std::string> lines;
    while (read_child(c, lines)) {
    }
    int status = 0;
    ASSERT_TRUE(wait_child(c, 10, status));
    EXPECT_EQ(lines, (std::vector<std::string>{"one", "two", "three"}));
    EXPECT_EQ(describe_status(status), "exit status 3");
}

TEST(ChildProcess, AMissingProgramExitsWith127AndSaysSo)
{
    Child c;
    std::string err;
    ASSERT_TRUE(start_child({"/no/such/program"}, "", 0, c, err));
    std::vector<std::string> lines;
    while (read_child(c, lines)) {
    }
    int status = 0;
    ASSERT_TRUE(wait_child(c, 10, status));
    EXPECT_EQ(WEXITSTATUS(status), 127);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("cannot run /no/such/program"), std::string::npos);
}

TEST(ChildProcess, WaitIsBoundedAndKillEndsIt)
{
    Child c;
    std::string err;
    ASSERT_TRUE(start_child({"/bin/sleep", "30"}, "", 0, c, err));
    int status = 0;
    EXPECT_FALSE(wait_child(c, 0.05, status));
    kill_child(c);
    EXPECT_EQ(c.pid, -1);
    kill_child(c);      // twice is harmless
}
