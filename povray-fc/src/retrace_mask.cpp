// The re-traced pixel mask of a frame, written with OpenImageIO.
#include "povrayfc/retrace_mask.h"

#include <cstdio>
#include <memory>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace povrayfc {

bool WriteRetraceMask(const std::string &path, const DirtyMask &traced, std::string &error) {
    const int w = traced.Width(), h = traced.Height();
    std::vector<unsigned char> pixels(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) pixels[std::size_t(y) * w + x] = traced.Test(x, y) ? 255 : 0;
    // The temporary keeps the .png extension so OpenImageIO picks the format.
    const std::string temporary = path + ".tmp.png";
    auto out = OIIO::ImageOutput::create(temporary);
    if (!out) {
        error = path + ": " + OIIO::geterror();
        return false;
    }
    OIIO::ImageSpec spec(w, h, 1, OIIO::TypeDesc::UINT8);
    if (!out->open(temporary, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close()) {
        error = path + ": " + out->geterror();
        std::remove(temporary.c_str());
        return false;
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        error = path + ": cannot rename the temporary file into place";
        std::remove(temporary.c_str());
        return false;
    }
    return true;
}

}  // namespace povrayfc
