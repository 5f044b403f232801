// fc_image_plugin.cpp - fc-image.so: the OpenImageIO calls of fc-master, as a plugin.
//
// OpenImageIO pulls in some 260 shared libraries, whose symbols take the dynamic loader about
// 0.35 s to bind (measured: fc-master --help 0.39 s linked with it, 0.006 s without); as a
// plugin it loads on a background thread while the master probes the scene (master/image_codec.h).
//
// Images are encoded into memory, not written to a file: fc-master writes the bytes itself, so
// that every write, fsync and close is checked (a full disk must be an error, never a short
// frame) and the size on disk can be compared with the encoded size before the rename.
// Pixel types: 0 = uint8, 1 = uint16, 2 = half; always 3 channels, rows top first.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/half.h>
#include <OpenImageIO/imageio.h>

namespace {

OIIO::TypeDesc pixel_type(int type)
{
    switch (type) {
    case 0: return OIIO::TypeDesc::UINT8;
    case 1: return OIIO::TypeDesc::UINT16;
    case 2: return OIIO::TypeDesc::HALF;
    default: return OIIO::TypeDesc::UNKNOWN;
    }
}

void set_error(char *error, size_t size, const std::string &msg)
{
    std::snprintf(error, size, "%s", msg.c_str());
}

} // namespace

// Encode a 3-channel image in `format` (an OpenImageIO format name: "targa", "png",
// "openexr") with the given compression ("" = the format's default, "fast" = the quickest
// encoding the format has) into a malloc'd buffer (*out, *out_size; free it with
// fc_image_free). Returns 1, or 0 with error filled.
extern "C" int fc_image_encode(const char *format, int width, int height, int type,
                               const void *pixels, const char *compression, unsigned char **out,
                               size_t *out_size, char *error, size_t error_size)
{
    OIIO::TypeDesc td = pixel_type(type);
    auto output = OIIO::ImageOutput::create(format);
    if (!output || td == OIIO::TypeDesc::UNKNOWN) {
        set_error(error, error_size, std::string("OpenImageIO cannot write ") + format + ": " +
                                         OIIO::geterror());
        return 0;
    }
    if (!output->supports("ioproxy")) {
        set_error(error, error_size, std::string("OpenImageIO cannot encode ") + format +
                                         " into memory");
        return 0;
    }
    OIIO::ImageSpec spec(width, height, 3, td);
    if (compression && std::strcmp(compression, "fast") == 0) {
        // PNG: no row filter and zlib level 1 encode 5x faster than OpenImageIO's default
        // (every filter tried on each row, level 6), for a file about as small (measured on
        // a contact sheet of Newton frames: 27 ms against 137 ms, 676 KB against 645 KB).
        // OpenImageIO 2.4's PNG writer ignores "compression" = "zip:N".
        if (std::strcmp(format, "png") == 0) {
            spec.attribute("png:filter", 8);    // PNG_FILTER_NONE
            spec.attribute("png:compressionLevel", 1);
        }
    } else if (compression && *compression) {
        spec.attribute("compression", compression);
    }
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    // The name only tells the writer which file it writes; the bytes go to the proxy.
    if (!output->set_ioproxy(&proxy) || !output->open("memory", spec) || !output->write_image(td, pixels) || !output->close()) {
        set_error(error, error_size, output->geterror());
        return 0;
    }
    *out = static_cast<unsigned char *>(std::malloc(bytes.size() ? bytes.size() : 1));
    if (!*out) {
        set_error(error, error_size, "out of memory");
        return 0;
    }
    std::memcpy(*out, bytes.data(), bytes.size());
    *out_size = bytes.size();
    return 1;
}

extern "C" void fc_image_free(void *p)
{
    std::free(p);
}

// Read the whole image at path as 3 channels of `type` into a malloc'd buffer (*pixels; free
// it with fc_image_free); *channels is the file's channel count. A truncated or damaged file
// is an error: the reader must deliver every pixel. Returns 1, or 0 with error filled.
extern "C" int fc_image_read(const char *path, int type, int *width, int *height, int *channels,
                             void **pixels, char *error, size_t error_size)
{
    OIIO::TypeDesc td = pixel_type(type);
    auto input = OIIO::ImageInput::open(path);
    if (!input) {
        set_error(error, error_size, OIIO::geterror());
        return 0;
    }
    const OIIO::ImageSpec &spec = input->spec();
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    if (spec.nchannels < 3 || spec.width <= 0 || spec.height <= 0) {
        set_error(error, error_size, "not a colour image");
        return 0;
    }
    size_t bytes = size_t(spec.width) * size_t(spec.height) * 3 * td.size();
    void *buf = std::malloc(bytes);
    if (!buf) {
        set_error(error, error_size, "out of memory");
        return 0;
    }
    bool ok = input->read_image(0, 0, 0, 3, td, buf);
    std::string msg = input->geterror();
    input->close();
    if (!ok || !msg.empty()) {
        std::free(buf);
        set_error(error, error_size, msg.empty() ? "cannot read the pixels" : msg);
        return 0;
    }
    *pixels = buf;
    return 1;
}

// Convert floats to half floats (OpenEXR's rounding, as POV-Ray's OpenEXR writer converts).
extern "C" void fc_image_float_to_half(const float *in, uint16_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        Imath::half h(in[i]);
        out[i] = h.bits();
    }
}

// Convert half floats to floats.
extern "C" void fc_image_half_to_float(const uint16_t *in, float *out, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        Imath::half h;
        h.setBits(in[i]);
        out[i] = float(h);
    }
}
