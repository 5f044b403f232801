// output_dir_test.cpp - the output directory: one master at a time, the manifest and its
// differences, the record of frames written (lines cut short are ignored).
#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "files.h"
#include "output_dir.h"
#include "text.h"
#include "temp_dirs.h"

using namespace fc;

TEST(OutputDir, OneMasterAtATime)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-output-dir-test-", dir, err)) << err;
    {
        OutputDir a, b;
        ASSERT_TRUE(a.open(dir + "/out", "clk.tga", err)) << err;
        EXPECT_FALSE(b.open(dir + "/out", "clk.tga", err));
        EXPECT_NE(err.find(strf("another fc-master (pid %d) is writing frames into", int(getpid()))),
                  std::string::npos)
            << err;
    }
    remove_tree(dir);
}

TEST(OutputDir, ManifestDifferencesAndTheRecordOfFrames)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-output-dir-test-", dir, err)) << err;
    {
        OutputDir d;
        ASSERT_TRUE(d.open(dir, "clk.tga", err)) << err;
        EXPECT_FALSE(d.has_previous());
        ASSERT_TRUE(d.start_run({{"option Width", "320"}, {"scene", "a.pov"}}, true, err)) << err;
        FrameInputs in;
        FrameInputs::File scene;
        scene.path = "/anim/clk.pov";
        scene.contents = 0xabcd;
        in.files.push_back(scene);
        FrameInputs::File absent;
        absent.read = false;
        absent.path = "/anim/col.inc";
        in.files.push_back(absent);
        ASSERT_TRUE(d.record("clk01.tga", 0x1234, in, err)) << err;
        FrameInputs unknown;
        unknown.known = false;
        ASSERT_TRUE(d.record("clk03.tga", 0x5678, unknown, err)) << err;
        ASSERT_TRUE(d.sync_records(err)) << err;
    }
    // A line cut short by a full disk names no frame.
    int fd = open((dir + "/.fc-master/clk.tga.frames").c_str(), O_WRONLY | O_APPEND);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(write(fd, "clk02.tga w1 00ab", 17), 17);
    close(fd);
    OutputDir d;
    ASSERT_TRUE(d.open(dir, "clk.tga", err)) << err;
    ASSERT_TRUE(d.has_previous());
    std::vector<std::string> diffs = d.differences({{"option Width", "640"}, {"option Height", "480"}});
    EXPECT_EQ(diffs, (std::vector<std::string>{"option Height is new: 480",
                                                "option Width: 320 -> 640",
                                                "scene is gone (was a.pov)"}));
    uint64_t hash = 0;
    bool words = false;
    EXPECT_TRUE(d.recorded("clk01.tga", hash, words));
    EXPECT_EQ(hash, 0x1234u);
    EXPECT_TRUE(words);
    EXPECT_FALSE(d.recorded("clk02.tga", hash, words));
    // The inputs come back as they were recorded; unknown ones as unknown.
    FrameInputs in;
    ASSERT_TRUE(d.recorded_inputs("clk01.tga", in));
    ASSERT_TRUE(in.known);
    ASSERT_EQ(in.files.size(), 2u);
    EXPECT_EQ(in.files[0].path, "/anim/clk.pov");
    EXPECT_EQ(in.files[0].contents, 0xabcdu);
    EXPECT_FALSE(in.files[1].read);
    ASSERT_TRUE(d.recorded_inputs("clk03.tga", in));
    EXPECT_FALSE(in.known);
    remove_tree(dir);
}

TEST(OutputDir, RecordsOfEarlierVersionsStillVerify)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-output-dir-test-", dir, err)) << err;
    ASSERT_TRUE(make_dirs(dir + "/.fc-master", err));
    ASSERT_TRUE(write_text(dir + "/.fc-master/clk.tga.frames",
                           "clk01.tga w1 00000000000000ab\nclk02.tga 00000000000000cd\n", err));
    OutputDir d;
    ASSERT_TRUE(d.open(dir, "clk.tga", err)) << err;
    uint64_t hash = 0;
    bool words = false;
    ASSERT_TRUE(d.recorded("clk01.tga", hash, words));
    EXPECT_TRUE(words && hash == 0xab);
    ASSERT_TRUE(d.recorded("clk02.tga", hash, words));
    EXPECT_TRUE(!words && hash == 0xcd);
    FrameInputs in;
    EXPECT_FALSE(d.recorded_inputs("clk01.tga", in));     // none recorded then
    remove_tree(dir);
}
