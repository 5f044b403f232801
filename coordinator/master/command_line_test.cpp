// command_line_test.cpp - fc-master's options: ours parsed, POV-Ray's kept in order, and every
// mistake one line that names the option.
#include <cstdio>

#include <gtest/gtest.h>

#include "command_line.h"
#include "files.h"
#include "temp_dirs.h"

using namespace fc;

namespace {

bool parse(std::vector<std::string> args, Options &o, std::string &err)
{
    bool help = false;
    return parse_command_line(args, o, help, err);
}

} // namespace

TEST(CommandLine, OursParsedPovRaysKept)
{
    Options o;
    std::string err;
    ASSERT_TRUE(parse({"--division", "sequence", "scene.ini", "+W320", "-o", "out", "--keep-going",
                       "+O/tmp/x.png", "--timeout=30"},
                      o, err))
        << err;
    EXPECT_EQ(o.division, Division::Sequence);
    EXPECT_EQ(o.output, "out");
    EXPECT_TRUE(o.keep_going);
    EXPECT_DOUBLE_EQ(o.timeout, 30);
    EXPECT_EQ(o.pov, (std::vector<std::string>{"scene.ini", "+W320", "+O/tmp/x.png"}));
    EXPECT_EQ(o.slaves, 1);     // frame coherence: one slave per host
    bool help = false;
    ASSERT_TRUE(parse_command_line({"scene.ini", "--help"}, o, help, err));
    EXPECT_TRUE(help);
}

TEST(CommandLine, ARepeatedOutputIsAnErrorNotAScene)
{
    Options o;
    std::string err;
    EXPECT_FALSE(parse({"-o", "out", "-o", "scene.ini"}, o, err));
    EXPECT_EQ(err, "-o given twice (out, then scene.ini)");
    EXPECT_FALSE(parse({"scene.ini", "--output", "a", "-o", "b"}, o, err));
    EXPECT_EQ(err, "-o given twice (a, then b)");
}

TEST(CommandLine, MistakesNameTheOption)
{
    Options o;
    std::string err;
    EXPECT_FALSE(parse({"scene.ini", "--tile", "4"}, o, err));
    EXPECT_EQ(err, "--tile must be a whole number of pixels >= 8, not '4'");
    EXPECT_FALSE(parse({"scene.ini", "--frobnicate"}, o, err));
    EXPECT_EQ(err, "unknown option --frobnicate");
    EXPECT_FALSE(parse({"scene.ini", "--no-fc=1"}, o, err));
    EXPECT_EQ(err, "option --no-fc takes no value");
    EXPECT_FALSE(parse({"--quiet"}, o, err));
    EXPECT_EQ(err, "no scene given");
    EXPECT_FALSE(parse({"scene.ini", "--hostfile", "/no/such/hosts"}, o, err));
    EXPECT_EQ(err, "--hostfile /no/such/hosts: No such file or directory");
}

TEST(CommandLine, AHostFileWithoutHostsIsAnError)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-command-line-test-", dir, err));
    ASSERT_TRUE(write_text(dir + "/hosts", "# the cluster\n* ep=/opt/bin\n\n", err));
    Options o;
    EXPECT_FALSE(parse({"scene.ini", "--hostfile", dir + "/hosts"}, o, err));
    EXPECT_EQ(err, "--hostfile " + dir + "/hosts names no host");
    ASSERT_TRUE(write_text(dir + "/hosts", "# the cluster\nnode2 ep=/opt/bin\n", err));
    EXPECT_TRUE(parse({"scene.ini", "--hostfile", dir + "/hosts"}, o, err)) << err;
    remove_tree(dir);
}
