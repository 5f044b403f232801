// The reads collection as the renderer's hooks and its frame channel use it.
#include "frame-channel/parse_reads.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace fc {
namespace {

TEST(ParseReads, OffItCollectsNothing)
{
    ParseReads reads;
    reads.opened("scene.pov");
    reads.absent("data.txt");
    // Invariant: without a frame channel the hooks leave no trace.
    EXPECT_EQ(reads.take(), "");
}

TEST(ParseReads, LinesComeOnceInTheOrderFirstMet)
{
    ParseReads reads;
    reads.enable(true);
    reads.opened("scene.pov");
    reads.absent("colors.inc");
    reads.opened("/usr/share/povray-3.7/include/colors.inc");
    reads.opened("scene.pov");          // a macro of the scene file, called again
    reads.absent("colors.inc");
    reads.opened("");                   // nothing found, nothing opened: no line
    EXPECT_EQ(reads.take(), "F\tscene.pov\n"
                            "A\tcolors.inc\n"
                            "F\t/usr/share/povray-3.7/include/colors.inc\n");
    // Taken: the next record starts empty.
    EXPECT_EQ(reads.take(), "");
}

TEST(ParseReads, ANameWithALineBreakIsNeverSplitIntoLines)
{
    // A file named "x<LF>F<TAB>y" must not read as the files "x" and "y": the first would be
    // hashed in its place, and an edit of the real file missed on resume.
    ParseReads reads;
    reads.enable(true);
    reads.opened("scene.pov");
    reads.opened("x\nF\ty");
    reads.absent("gone\n.inc");
    EXPECT_EQ(reads.take(), "F\tscene.pov\n"
                            "U\tx F\ty\n"
                            "U\tgone .inc\n");
}

TEST(ParseReads, AFileAbsentAndThenReadHasBothLines)
{
    ParseReads reads;
    reads.enable(true);
    reads.absent("late.inc");
    reads.opened("late.inc");
    EXPECT_EQ(reads.take(), "A\tlate.inc\nF\tlate.inc\n");
}

TEST(ParseReads, EachFrameStartsAfresh)
{
    ParseReads reads;
    reads.enable(true);
    reads.opened("scene.pov");
    reads.opened("early.inc");
    reads.restart();                    // the next frame's parse
    reads.opened("scene.pov");
    EXPECT_EQ(reads.take(), "F\tscene.pov\n");
    reads.opened("a.inc");
    reads.enable(false);
    reads.opened("b.inc");
    EXPECT_EQ(reads.take(), "");
}

TEST(ParseReads, NotesFromTwoThreadsAreAllKept)
{
    ParseReads reads;
    reads.enable(true);
    auto note = [&reads](char kind) {
        for (int i = 0; i < 1000; i++) {
            std::string path = std::string(1, kind) + std::to_string(i);
            if (kind == 'f')
                reads.opened(path);
            else
                reads.absent(path);
        }
    };
    std::thread parser(note, 'f'), front_end(note, 'a');
    parser.join();
    front_end.join();
    std::string all = reads.take();
    size_t lines = 0;
    for (char c : all)
        lines += c == '\n';
    EXPECT_EQ(lines, 2000u);
    EXPECT_NE(all.find("F\tf999\n"), std::string::npos);
    EXPECT_NE(all.find("A\ta0\n"), std::string::npos);
}

} // namespace
} // namespace fc
