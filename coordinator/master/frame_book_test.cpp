// frame_book_test.cpp - every frame in one place: results marked cell by cell, a frame complete
// with its last cell, complete frames written in frame order under their final names, and
// frames that need no rendering kept out of the work.
#include <gtest/gtest.h>

#include "files.h"
#include "frame_book.h"
#include "temp_dirs.h"

using namespace fc;

namespace {

// A book of `frames` frames of 4x2 pixels, Targa, in a fresh directory: in two 2x2 tiles, or
// one tile of the whole frame (sequence division).
struct Shelf {
    std::string dir;
    OutputDir out;
    OutputFormat format;
    std::unique_ptr<FrameFiles> files;
    std::unique_ptr<FrameEncoder> encoder;
    std::unique_ptr<FrameBook> book;

    explicit Shelf(int frames, int tiles = 2)
    {
        std::string err;
        EXPECT_TRUE(make_temp_dir("/tmp", "fc-frame-book-test-", dir, err)) << err;
        EXPECT_TRUE(out.open(dir, "clk.tga", err)) << err;
        EXPECT_TRUE(out.start_run({{"scene", "clk.pov"}}, true, err)) << err;
        std::vector<int> numbers;
        for (int i = 0; i < frames; i++)
            numbers.push_back(i + 1);
        files.reset(new FrameFiles(out, format, "clk", 2, 4, 2, numbers));
        encoder.reset(new FrameEncoder(format, Division::Frame));
        book.reset(new FrameBook(*files, *encoder, 4, 2, numbers, tiles));
    }
    ~Shelf() { remove_tree(dir); }
};

// A result of tile t (0: left, 1: right) of frame `number`, its pixels all `value`.
FrameResult tile(int number, int t, uint8_t value)
{
    FrameResult r;
    r.frame = number;
    r.tiles = {t};
    r.rects = {Rect{2 * t, 0, 2 * t + 2, 2}};
    r.encoding = "rgb8";
    r.data.assign(2 * 2 * 3, value);
    return r;
}

// A whole frame (the one tile of sequence division) with POV-Ray's file of it.
FrameResult whole(int number, const std::string &file)
{
    FrameResult r;
    r.frame = number;
    r.tiles = {0};
    r.rects = {Rect{0, 0, 4, 2}};
    r.encoding = "rgb8";
    r.data.assign(4 * 2 * 3, 9);
    r.file.assign(file.begin(), file.end());
    return r;
}

} // namespace

TEST(FrameBook, AFrameIsCompleteWithItsLastCellAndWrittenInFrameOrder)
{
    Shelf s(3);
    FrameBook &b = *s.book;
    std::vector<int> fresh;
    std::string err;
    FrameResult left = tile(2, 0, 7);
    ASSERT_TRUE(b.deliver(b.index_of(2), left, fresh, err)) << err;
    EXPECT_EQ(fresh, std::vector<int>{0});
    EXPECT_EQ(b.state(1), FrameBook::State::Assembling);
    EXPECT_EQ(b.next_to_write(true), -1);
    // A second copy of the same cell adds nothing.
    FrameResult copy = tile(2, 0, 7);
    ASSERT_TRUE(b.deliver(1, copy, fresh, err));
    EXPECT_TRUE(fresh.empty());
    // Frame 3 completes first, frame 2 after it: 2 is written first.
    FrameResult three_left = tile(3, 0, 1), three_right = tile(3, 1, 2);
    ASSERT_TRUE(b.deliver(2, three_left, fresh, err)) << err;
    ASSERT_TRUE(b.deliver(2, three_right, fresh, err)) << err;
    FrameResult right = tile(2, 1, 8);
    ASSERT_TRUE(b.deliver(1, right, fresh, err)) << err;
    EXPECT_EQ(b.state(1), FrameBook::State::Complete);
    EXPECT_EQ(b.held(), 2u);
    EXPECT_EQ(b.next_to_write(true), 1);
    EXPECT_FALSE(b.all_rendered());     // frame 1 has no cell yet
    b.skip(0);
    EXPECT_TRUE(b.all_rendered());
    EXPECT_EQ(b.skipped_count(), 1);
}

TEST(FrameBook, AWholeFrameIsStoredAsPovRaysFileUnderItsFinalName)
{
    Shelf s(1, 1);
    FrameBook &b = *s.book;
    std::vector<int> fresh;
    std::string err;
    FrameResult r = whole(1, "POV-Ray's file");
    ASSERT_TRUE(b.deliver(0, r, fresh, err)) << err;
    std::vector<uint8_t> samples;
    bool disk_full = true;
    ASSERT_EQ(b.next_to_write(false), 0);
    ASSERT_TRUE(b.write(0, samples, disk_full, err)) << err;
    EXPECT_FALSE(disk_full);
    EXPECT_EQ(samples.size(), 4u * 2 * 3);          // for the preview
    std::string text;
    ASSERT_TRUE(read_text(s.dir + "/clk01.tga", text, err)) << err;
    EXPECT_EQ(text, "POV-Ray's file");
    EXPECT_FALSE(file_exists(s.dir + "/clk01.tga.fc-tmp"));
    EXPECT_EQ(b.state(0), FrameBook::State::Written);
    EXPECT_EQ(b.written_count(), 1);
    EXPECT_EQ(b.held(), 0u);
    uint64_t hash = 0;
    bool words = false;
    EXPECT_TRUE(s.out.recorded("clk01.tga", hash, words));
    EXPECT_EQ(hash, FrameFiles::pixels_hash(samples));
}

TEST(FrameBook, AMalformedResultIsAnError)
{
    Shelf s(1);
    std::vector<int> fresh;
    std::string err;
    FrameResult r = tile(1, 0, 1);
    r.data.pop_back();
    EXPECT_FALSE(s.book->deliver(0, r, fresh, err));
    EXPECT_EQ(err, "11 bytes of pixels for 4 pixels");
    FrameResult wide = tile(1, 1, 1);
    wide.rects[0].x1 = 5;
    EXPECT_FALSE(s.book->deliver(0, wide, fresh, err));
    EXPECT_NE(err.find("outside the 4x2 image"), std::string::npos) << err;
}

TEST(FrameBook, FramesThatNeedNoRenderingHaveTheirCellsDone)
{
    Shelf s(3);
    FrameBook &b = *s.book;
    b.resumed(0);
    b.give_up(1, "it hangs");
    b.give_up(1, "again");
    EXPECT_TRUE(b.cells().frame_done(0) && b.cells().frame_done(1));
    EXPECT_FALSE(b.cells().frame_done(2));
    EXPECT_EQ(b.resumed_count(), 1);
    EXPECT_EQ(b.given_up_count(), 1);
    EXPECT_EQ(b.given_up(), (std::vector<std::pair<int, std::string>>{{2, "it hangs"}}));
    EXPECT_TRUE(b.start(2));
    EXPECT_FALSE(b.start(2));           // its Pre_Frame_Command runs once
}
