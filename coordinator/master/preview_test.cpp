// preview_test.cpp - unit tests of when the live preview writes (no PVM, no renderer; nothing
// here needs OpenImageIO, whose loading is what a write starts with).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image_codec.h"
#include "preview.h"

using namespace fc;

// A write begins by loading OpenImageIO in the background: whether one was asked for.
static bool write_begun()
{
    return image_io_loading() || image_io_ready();
}

TEST(Preview, WritesOnlyWhenSomeoneCouldLook)
{
    char tmpl[] = "/tmp/fc-preview-test-XXXXXX";
    ASSERT_TRUE(mkdtemp(tmpl) != nullptr);
    const std::string dir = std::string(tmpl) + "/preview";
    const std::vector<uint8_t> frame(8 * 6 * 3, 128);
    std::string err;
    const double due = Preview::kFirstWrite + 0.1;

    // A render about to end when the first write is due: no write, neither then nor at its end.
    {
        Preview p;
        p.start(dir, 8, 6, PixelType::U8, 4, 0.0);
        p.add(0, frame);
        EXPECT_TRUE(p.flush(due, false, err, Preview::kMinTimeLeft / 2));
        EXPECT_TRUE(!write_begun());
        p.add(1, frame);
        EXPECT_TRUE(p.flush(due + 1, true, err));
        EXPECT_TRUE(!write_begun());
        EXPECT_TRUE(access(dir.c_str(), F_OK) != 0);
    }
    // A render with time to go: nothing before kFirstWrite, whatever its ETA; then the write.
    {
        Preview p;
        p.start(dir, 8, 6, PixelType::U8, 4, 0.0);
        p.add(0, frame);
        EXPECT_TRUE(p.flush(Preview::kFirstWrite - 0.1, false, err, 100));
        EXPECT_TRUE(!write_begun());
        EXPECT_TRUE(p.flush(due, false, err, Preview::kMinTimeLeft * 2));
        EXPECT_TRUE(write_begun());
    }
    wait_image_io();    // (fc-image.so is not beside this test: its loading fails, harmlessly)
    rmdir(tmpl);
}
