// frame_encoder.cpp - the one choice of how assembled frames are encoded (see frame_encoder.h).
#include "frame_encoder.h"

#include <cstdio>

#include "image_codec.h"
#include "image_writer_client.h"

namespace fc {

void FrameEncoder::preload_while_probing(Division division)
{
    // Not during the first frames instead: with fc a slave keeps its tiles, and the load would
    // hold the master host's slave back for the whole run.
    if (division != Division::Sequence && !image_writer_present())
        preload_image_io();
}

FrameEncoder::FrameEncoder(const OutputFormat &format, Division division)
    : format_(format), division_(division),
      by_writer_(format.oiio == "targa" && format.pixels == PixelType::U8 && image_writer_present())
{
}

void FrameEncoder::preload_for_run() const
{
    // OpenEXR's half floats are made by OpenImageIO as the frames arrive; assembled PNG
    // frames are encoded by it.
    if (format_.pixels == PixelType::Half || (division_ != Division::Sequence && !by_writer_))
        preload_image_io();
}

void FrameEncoder::result_without_file() const
{
    if (!by_writer_)
        preload_image_io();
}

bool FrameEncoder::waits_for_image_io() const
{
    return image_io_loading() && !by_writer_;
}

bool FrameEncoder::encode(int width, int height, const void *samples, double file_gamma,
                          std::vector<uint8_t> &out, std::string &err)
{
    if (by_writer_ && !writer_failed_) {
        std::string why;
        if (writer_encode_targa(width, height, format_.compression == "rle", file_gamma,
                                static_cast<const uint8_t *>(samples), out, why))
            return true;
        // Same pixels from OpenImageIO: the frame is not lost, the run only pays its load.
        writer_failed_ = true;
        std::string message = why + "; encoding Targa frames with OpenImageIO";
        if (warn_)
            warn_(message);
        else
            fprintf(stderr, "fc-master: warning: %s\n", message.c_str());
    }
    return encode_with_image_io(format_.oiio, format_.compression, width, height, format_.pixels,
                                samples, out, err);
}

size_t FrameEncoder::frame_bytes_bound(int width, int height) const
{
    size_t raw = size_t(width) * size_t(height) * 3 * pixel_type_bytes(format_.pixels);
    // Run-length Targa at its worst adds a byte per 128 pixels, PNG's stored deflate blocks
    // 5 bytes per 64 KiB and a byte per row; headers and metadata stay far below 64 KiB.
    return raw + raw / 64 + size_t(height) + (64u << 10);
}

size_t FrameEncoder::frame_bytes(int width, int height, bool &exact)
{
    exact = false;
    if (format_.fixed_size) {
        // An uncompressed format: a header and a footer of fixed size around the samples, so
        // two blank frames of one and two pixels tell the size of any.
        std::vector<uint8_t> blank(6 * pixel_type_bytes(format_.pixels), 0), one, two;
        std::string err;
        if (encode(1, 1, blank.data(), 0, one, err) && encode(2, 1, blank.data(), 0, two, err) &&
            two.size() > one.size()) {
            size_t per_pixel = two.size() - one.size();
            exact = true;
            return one.size() - per_pixel + per_pixel * size_t(width) * size_t(height);
        }
    }
    return frame_bytes_bound(width, height);
}

} // namespace fc
