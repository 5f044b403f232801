// preview_test.cpp - unit tests of when the live preview writes (no PVM, no renderer; nothing
// here needs OpenImageIO, whose loading is what a write starts with).
// Run: make -C coordinator test-preview
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "check.h"
#include "image_io.h"
#include "preview.h"

using namespace fc;

// A write begins by loading OpenImageIO in the background: whether one was asked for.
static bool write_begun()
{
    return image_io_loading() || image_io_ready();
}

int main()
{
    char tmpl[] = "/tmp/fc-preview-test-XXXXXX";
    if (!mkdtemp(tmpl)) {
        perror("mkdtemp");
        return 1;
    }
    const std::string dir = std::string(tmpl) + "/preview";
    const std::vector<uint8_t> frame(8 * 6 * 3, 128);
    std::string err;
    const double due = Preview::kFirstWrite + 0.1;

    // A render about to end when the first write is due: no write, neither then nor at its end.
    {
        Preview p;
        p.start(dir, 8, 6, PixelType::U8, 4, 0.0);
        p.add(0, frame);
        CHECK(p.flush(due, false, err, Preview::kMinTimeLeft / 2));
        CHECK(!write_begun());
        p.add(1, frame);
        CHECK(p.flush(due + 1, true, err));
        CHECK(!write_begun());
        CHECK(access(dir.c_str(), F_OK) != 0);
    }
    // A render with time to go: nothing before kFirstWrite, whatever its ETA; then the write.
    {
        Preview p;
        p.start(dir, 8, 6, PixelType::U8, 4, 0.0);
        p.add(0, frame);
        CHECK(p.flush(Preview::kFirstWrite - 0.1, false, err, 100));
        CHECK(!write_begun());
        CHECK(p.flush(due, false, err, Preview::kMinTimeLeft * 2));
        CHECK(write_begun());
    }
    wait_image_io();    // (fc-image.so is not beside this test: its loading fails, harmlessly)
    rmdir(tmpl);
    return check_summary("preview_test");
}
