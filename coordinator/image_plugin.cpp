// image_plugin.cpp - fc-image.so: the OpenImageIO calls of fc-master, as a plugin.
//
// OpenImageIO pulls in some 260 shared libraries, whose symbols take the dynamic loader about
// 0.35 s to bind (measured: fc-master --help 0.39 s linked with it, 0.006 s without); as a
// plugin it loads on a background thread while the master probes the scene (image_io.h).
#include <cstddef>
#include <cstdio>

#include <OpenImageIO/imageio.h>

// Write an 8-bit RGB image (Targa, uncompressed). Returns 1, or 0 with error filled.
extern "C" int fc_image_write_targa(const char *path, int width, int height,
                                    const unsigned char *rgb, char *error, size_t error_size)
{
    auto out = OIIO::ImageOutput::create("tga");
    if (!out) {
        std::snprintf(error, error_size, "OpenImageIO has no Targa writer: %s",
                      OIIO::geterror().c_str());
        return 0;
    }
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("compression", "none");
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb) ||
        !out->close()) {
        std::snprintf(error, error_size, "%s", out->geterror().c_str());
        return 0;
    }
    return 1;
}

// Size and channels of an image file. Returns 1, or 0 when it cannot be read as an image.
extern "C" int fc_image_size(const char *path, int *width, int *height, int *channels)
{
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        return 0;
    const OIIO::ImageSpec &spec = in->spec();
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    in->close();
    return 1;
}
