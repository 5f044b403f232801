// frame_inputs_test.cpp - the files a frame depends on: parsed from the renderer's report,
// hashed, and compared with what a resume finds.
#include <unistd.h>

#include <gtest/gtest.h>

#include "files.h"
#include "frame_inputs.h"
#include "temp_dirs.h"

using namespace fc;

TEST(FrameInputs, ParsedAbsoluteAndOnce)
{
    FrameInputs in;
    std::string err;
    ASSERT_TRUE(parse_reads("F\tscene.pov\nF\t/usr/share/povray/include/colors.inc\n"
                            "A\tcol.inc\nF\tscene.pov\n", "/home/u/anim", in, err)) << err;
    ASSERT_EQ(in.files.size(), 3u);
    EXPECT_EQ(in.files[0].path, "/home/u/anim/scene.pov");
    EXPECT_TRUE(in.files[0].read);
    EXPECT_EQ(in.files[2].path, "/home/u/anim/col.inc");
    EXPECT_FALSE(in.files[2].read);
    EXPECT_FALSE(parse_reads("X\tnothing\n", "/", in, err));
    EXPECT_EQ(err, "malformed line in the files a frame read: X\tnothing");
    // A name with a line break, as the renderer reports it: the inputs cannot be known.
    FrameInputs unknowable;
    EXPECT_FALSE(parse_reads("F\tscene.pov\nU\tx F\ty\n", "/", unknowable, err));
    EXPECT_NE(err.find("has a line break (x F\ty)"), std::string::npos) << err;
}

TEST(FrameInputs, AnEditedReadFileOrAnAbsentOneThatAppearedIsAChange)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-frame-inputs-test-", dir, err));
    ASSERT_TRUE(write_text(dir + "/scene.pov", "#include \"col.inc\"\n", err));
    ASSERT_TRUE(write_text(dir + "/col.inc", "#declare C = 1;\n", err));
    FrameInputs in;
    ASSERT_TRUE(parse_reads("F\tscene.pov\nF\tcol.inc\nA\tmissing.inc\n", dir, in, err));
    InputHashes hashes;
    hashes.fill(in);
    ASSERT_TRUE(in.known);
    std::string id = in.id();
    EXPECT_EQ(id.size(), 16u);
    EXPECT_TRUE(hashes.changed(in).empty());

    // A new hasher (the next run) sees the edit by the contents, whatever the file's time.
    ASSERT_TRUE(write_text(dir + "/col.inc", "#declare C = 2;\n", err));
    InputHashes next;
    EXPECT_EQ(next.changed(in), std::vector<std::string>{dir + "/col.inc"});
    ASSERT_TRUE(write_text(dir + "/col.inc", "#declare C = 1;\n", err));
    EXPECT_TRUE(InputHashes().changed(in).empty());
    ASSERT_TRUE(write_text(dir + "/missing.inc", "", err));
    EXPECT_EQ(InputHashes().changed(in), std::vector<std::string>{dir + "/missing.inc"});
    unlink((dir + "/missing.inc").c_str());
    unlink((dir + "/col.inc").c_str());
    EXPECT_EQ(InputHashes().changed(in), std::vector<std::string>{dir + "/col.inc"});
    remove_tree(dir);
}

TEST(FrameInputs, AFileChangedDuringTheFrameIsNotKnown)
{
    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-frame-inputs-test-", dir, err));
    ASSERT_TRUE(write_text(dir + "/scene.pov", "sphere{0,1}\n", err));
    FrameInputs in;
    ASSERT_TRUE(parse_reads("F\tscene.pov\n", dir, in, err));
    // The frame began an hour ago: the file, written just now, may not be what it read.
    InputHashes().fill(in, double(time(nullptr)) - 3600);
    EXPECT_FALSE(in.known);
    EXPECT_EQ(in.id(), "");
    EXPECT_FALSE(InputHashes().changed(in).empty());
    remove_tree(dir);
}
