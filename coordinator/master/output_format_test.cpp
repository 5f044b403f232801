// output_format_test.cpp - the format POV-Ray's resolved options name, what the slaves are
// told to write, and the frames no format or memory can hold, refused before rendering.
#include <gtest/gtest.h>

#include "output_format.h"

using namespace fc;

TEST(OutputFormat, ResolvedOptionsNameTheFormat)
{
    OutputFormat f;
    std::string err;
    ASSERT_TRUE(output_format({{"Output_File_Type", "N"}, {"Bits_Per_Color", "12"}}, f, err));
    EXPECT_EQ(f.name, "PNG");
    EXPECT_EQ(f.encoding, "rgb16");
    EXPECT_EQ(format_option(f), "+FN12");
    ASSERT_TRUE(output_format({{"Output_File_Type", "C"}}, f, err));
    EXPECT_EQ(format_option(f), "+FC");
    ASSERT_TRUE(output_format({}, f, err));             // POV-Ray's own default
    EXPECT_EQ(format_option(f), "+FT");
    EXPECT_FALSE(output_format({{"Output_File_Type", "J"}}, f, err));
    EXPECT_EQ(err, "output file type JPEG (Output_File_Type=J, +FJ) is not supported: fc-master "
                   "writes Targa (+FT), RLE Targa (+FC), PNG (+FN) and OpenEXR (+FE)");
    EXPECT_FALSE(output_format({{"Output_File_Type", "N"}, {"Output_Alpha", "On"}}, f, err));
}

TEST(OutputFormat, ImpossibleFramesAreRefusedWithOneLine)
{
    OutputFormat targa, png;
    std::string err;
    ASSERT_TRUE(output_format({}, targa, err));
    ASSERT_TRUE(output_format({{"Output_File_Type", "N"}}, png, err));
    const double gigabytes = 1024.0 * 1024 * 1024;
    EXPECT_TRUE(frame_size_possible(targa, "rgb8", 65535, 480, 8 * gigabytes, err));
    EXPECT_FALSE(frame_size_possible(targa, "rgb8", 70000, 480, 8 * gigabytes, err));
    EXPECT_EQ(err, "a Targa frame holds at most 65535 pixels a side, not 70000x480: use PNG "
                   "(+FN) or OpenEXR (+FE)");
    EXPECT_TRUE(frame_size_possible(png, "rgb8", 70000, 480, 8 * gigabytes, err));
    EXPECT_FALSE(frame_size_possible(png, "rgb8", 100000, 100000, 8 * gigabytes, err));
    EXPECT_EQ(err, "a frame of 100000x100000 pixels needs 55.88 GB of fc-master's memory (its "
                   "samples and its file), more than this machine's 8.00 GB");
    EXPECT_EQ(err.find('\n'), std::string::npos);
}
