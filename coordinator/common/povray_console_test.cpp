// povray_console_test.cpp - what fc-master and fc-slave make of POV-Ray's console after a
// failure: the error lines without the noise, and whose fault it was.
#include <gtest/gtest.h>

#include "povray_console.h"

using namespace fc;

TEST(PovrayConsole, ErrorExcerptStartsAtTheFirstErrorAndDropsNoise)
{
    std::vector<std::string> tail = {
        "povray-fc: cannot open the user configuration file /root/.povray/3.7/povray.conf",
        "Parsing...",
        "File: scene.pov  Line: 7",
        "Parse Error: Expected 'object', undeclared identifier 'Foo' found instead",
        "Rendered 0 of 19200 pixels",
        "Fatal error in parser: Cannot parse input.",
    };
    EXPECT_EQ(error_excerpt(tail),
              "Parse Error: Expected 'object', undeclared identifier 'Foo' found instead\n"
              "Fatal error in parser: Cannot parse input.\n");
    EXPECT_TRUE(is_scene_error(tail));
}

TEST(PovrayConsole, AHostFailureIsNotTheScenes)
{
    std::vector<std::string> tail = {"Rendering frame 3", "fc: cannot run /no/povray-fc "
                                                          "(missing or not executable)"};
    EXPECT_FALSE(is_scene_error(tail));
    EXPECT_EQ(failure_excerpt(tail), "fc: cannot run /no/povray-fc (missing or not executable)\n");
    // Without an error line, the last lines that are not noise say what happened.
    std::vector<std::string> quiet = {"====", "Rendering frame 3", "Rendered 10 of 100 pixels"};
    EXPECT_EQ(failure_excerpt(quiet), "Rendering frame 3\n");
}
