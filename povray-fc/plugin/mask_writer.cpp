// povrayfc-mask.so: writes fc's re-traced pixel masks with OpenImageIO.
//
// A plugin rather than part of libpovrayfc: OpenImageIO pulls in some 240 shared
// libraries, and with Debian's -z now every symbol of them is bound when povray-fc
// starts (measured: +0.03 s wall per process, more than a tiny frame takes to render).
// libpovrayfc loads this only when Frame_Coherence_Mask is set.
#include <cstdio>
#include <vector>

#include <OpenImageIO/imageio.h>

extern "C" int povrayfc_write_mask(const char *path, int width, int height, const unsigned char *pixels,
                                   char *error, std::size_t errorSize) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        std::snprintf(error, errorSize, "%s", OIIO::geterror().c_str());
        return 0;
    }
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels) || !out->close()) {
        std::snprintf(error, errorSize, "%s", out->geterror().c_str());
        return 0;
    }
    return 1;
}
