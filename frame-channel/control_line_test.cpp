// Frame-control lines as fc-slave writes them and the renderer reads them.
#include "frame-channel/control_line.h"

#include <gtest/gtest.h>

#include <string>

namespace fc {
namespace {

TEST(ControlLine, RenderLinesReadBackAsWritten)
{
    std::vector<Rect> rects = {Rect{0, 0, 64, 64}, Rect{64, 0, 100, 37}};
    std::string line = render_control_line(12, rects);
    EXPECT_EQ(line, "render 12 0,0,64,64 64,0,100,37\n");
    ControlLine c;
    std::string err;
    ASSERT_TRUE(parse_control_line(line.substr(0, line.size() - 1), c, err)) << err;
    EXPECT_EQ(c.verb, ControlLine::kRender);
    EXPECT_EQ(c.frame, 12);
    EXPECT_EQ(c.rects, rects);

    ASSERT_TRUE(parse_control_line("render 3", c, err)) << err;
    EXPECT_EQ(c.verb, ControlLine::kRender);
    EXPECT_EQ(c.frame, 3);
    EXPECT_TRUE(c.rects.empty());
}

TEST(ControlLine, StopAndBlankLines)
{
    ControlLine c;
    std::string err;
    ASSERT_TRUE(parse_control_line("stop", c, err));
    EXPECT_EQ(c.verb, ControlLine::kStop);
    ASSERT_TRUE(parse_control_line("   ", c, err));
    EXPECT_EQ(c.verb, ControlLine::kNone);
}

TEST(ControlLine, MalformedLinesNameWhatIsWrong)
{
    ControlLine c;
    std::string err;
    EXPECT_FALSE(parse_control_line("rendr 1", c, err));
    EXPECT_EQ(err, "cannot understand 'rendr 1'");
    EXPECT_FALSE(parse_control_line("render", c, err));
    EXPECT_EQ(err, "cannot understand 'render'");
    EXPECT_FALSE(parse_control_line("render 1 10,10,5,20", c, err));
    EXPECT_EQ(err, "bad rectangle '10,10,5,20' in 'render 1 10,10,5,20'");
    EXPECT_FALSE(parse_control_line("render 1 0,0,5,5x", c, err));
    EXPECT_FALSE(parse_control_line("render 1 -1,0,5,5", c, err));
}

} // namespace
} // namespace fc
