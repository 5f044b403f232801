// fc_image_writer.cpp - fc-image-writer: POV-Ray's own image code for the frames fc-master
// assembles from tiles, in a process of its own beside fc-master
// (coordinator/master/image_writer_client.h is the other end). It links the patched POV-Ray's
// libraries (libpovray.a, libvfe.a), so it is built once POV-Ray is.
//
// Why a process: a frame division assembles every frame from tiles and must encode it.
// OpenImageIO's 262 shared libraries cost the dynamic loader 0.35-0.4 s of CPU to bind
// (166,000 symbol lookups, LD_DEBUG=statistics; fc-image.so), which on the master's host
// comes out of its slave's time: a fifth of a 320x240 Newton run on the emulated cluster.
// This program is POV-Ray's image code from the patched build (its objects are compiled for
// an executable, -fPIE, so they cannot go into a plugin, and the image code reaches most of
// POV-Ray) with POV-Ray's 22 libraries: about 2 ms to start.
//
// Two requests (protocol.h):
// - Targa files: the pixels arrive encoded (the frame channel sends what POV-Ray's Targa
//   writer stores): they go into the image as v / 255.0f and are written with a curve that
//   keeps them and no dither, so every stored value passes through unchanged
//   (floor(x * 255 + 0.5) = v), and the file records the gamma the renderer's file would.
//   The frames are then the files one POV-Ray process writes, header and footer included,
//   as a frame rendered whole already is (the renderer sends POV-Ray's own file of it).
// - Diffusion dithering (Dither_Method d1, d2, fs): each pixel's error goes to its
//   neighbours across the whole frame, so the renderers send the values their writer would
//   quantise, and the assembled frame is dithered here, by POV-Ray's own dither handler
//   through the renderer's gamma curve, pixel by pixel in raster order as its writers do.
//
// The program ends at the end of its requests (fc-master closed them) or on a broken pipe.
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

// configbase.h must be the first POV-Ray header (POV-Ray's rule for base/ files).
#include "base/configbase.h"
#include "base/fileinputoutput.h"
#include "base/povmsgid.h"
#include "base/image/colourspace.h"
#include "base/image/encoding.h"
#include "base/image/image.h"
#include "base/image/targa.h"
#include "image-writer/protocol.h"
#include "speedups/encode_memo.h"

namespace {

using fc_image_writer::kReplyMagic;
using fc_image_writer::kRequestMagic;
const int kRequests = fc_image_writer::kRequestFd, kReplies = fc_image_writer::kReplyFd;
const int kMaxSide = 1 << 16;                 // POV-Ray's images are at most this wide/high

// POV-Ray's output stream, writing into a buffer kept from frame to frame (a new one each
// frame was mostly page faults) instead of a named file.
class MemoryOStream : public pov_base::OStream
{
public:
    explicit MemoryOStream(std::vector<char> &buffer)
        : pov_base::OStream(pov_base::POV_File_Image_Targa)
    {
        f = fmemopen(buffer.data(), buffer.size(), "w");
        fail = (f == NULL);
    }
    ~MemoryOStream()
    {
        if (f != NULL)
            fclose(f);
        f = NULL;
    }

    // Flush and close the stream; false if anything failed (the buffer too small included).
    // size is then the number of bytes written.
    bool finish(size_t &size)
    {
        bool ok = !fail && f != NULL && fflush(f) == 0 && !ferror(f);
        long end = ok ? ftell(f) : -1;
        if (f != NULL && fclose(f) != 0)
            ok = false;
        f = NULL;
        size = end > 0 ? size_t(end) : 0;
        return ok && end > 0;
    }
};

// The values are stored already (v / 255 read back encodes to v): a curve that keeps them, and
// gives the Targa writer the gamma the renderer's curve had for its extension area.
class StoredValues : public pov_base::SimpleGammaCurve
{
public:
    explicit StoredValues(float file_gamma) : file_gamma_(file_gamma) {}
    float Encode(float x) const { return x; }
    float Decode(float x) const { return x; }
    float ApproximateDecodingGamma() const { return file_gamma_; }
    int GetTypeId() const { return kPOVList_GammaType_PowerLaw; }
    float GetParam() const { return file_gamma_; }

private:
    float file_gamma_;
};

bool read_fully(int fd, void *buf, size_t n, bool &eof)
{
    char *p = static_cast<char *>(buf);
    size_t got = 0;
    eof = false;
    errno = 0;
    while (got < n) {
        ssize_t r = read(fd, p + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0) {
            eof = (r == 0 && got == 0);
            return false;
        }
        got += size_t(r);
    }
    return true;
}

bool write_fully(int fd, const void *buf, size_t n)
{
    const char *p = static_cast<const char *>(buf);
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return false;
        p += w;
        n -= size_t(w);
    }
    return true;
}

bool reply(int ok, const void *data, uint64_t size)
{
    fc_image_writer::Reply head = {kReplyMagic, ok, size};
    return write_fully(kReplies, &head, sizeof head) && write_fully(kReplies, data, size_t(size));
}

// The image and curve kept from one request to the next: POV-Ray's Targa writer remembers the
// encoded pixels of the image it last wrote (speedups/encode_memo.h, the memo the renderer
// uses with frame coherence) and copies every span of a row whose stored floats did not change,
// so a frame that differs from the last in a few percent of its pixels costs a comparison
// per span instead of GetEncodedRGBAValue per pixel (8.5 ms a 320x240 frame).
struct Encoder {
    std::unique_ptr<pov_base::Image> image;
    int width = 0, height = 0;
    std::vector<unsigned char> last;    // the bytes the image holds (a row equal to its row
                                        // there is not set again)
    std::vector<char> file;             // the file written last (its first `size` bytes)
    pov_base::SimpleGammaCurvePtr curve;
    float file_gamma = -1;
};

// POV-Ray's Targa file of width x height RGB bytes, into enc.file's first `size` bytes; false
// with err.
// rgb's bytes are then the image's (enc.last), and rgb holds the previous ones.
bool encode_targa(Encoder &enc, int width, int height, bool rle, float file_gamma,
                  std::vector<unsigned char> &rgb, size_t &size, std::string &err)
{
    try {
        if (!enc.image || enc.width != width || enc.height != height) {
            enc.image.reset(pov_base::Image::Create(width, height, pov_base::Image::RGBFT_Float));
            enc.width = width;
            enc.height = height;
            enc.last.clear();
        }
        if (file_gamma <= 0)
            file_gamma = 1.0f;
        if (!enc.curve || enc.file_gamma != file_gamma) {
            enc.curve.reset(new StoredValues(file_gamma));
            enc.file_gamma = file_gamma;
        }
        // v / 255.0f encodes back to v: floor(v / 255.0f * 255 + 0.5) = v. Opaque.
        const size_t row_bytes = size_t(width) * 3;
        const bool have_last = enc.last.size() == row_bytes * size_t(height);
        // Only the pixels whose bytes changed are set again: the others hold the very floats
        // setting them would store (a frame of fc changes a few pixels of the rows it changes).
        for (int y = 0; y < height; y++) {
            const unsigned char *row = rgb.data() + row_bytes * size_t(y);
            const unsigned char *before = have_last ? &enc.last[row_bytes * size_t(y)] : nullptr;
            if (before != nullptr && std::memcmp(row, before, row_bytes) == 0)
                continue;
            for (int x = 0; x < width; x++, row += 3) {
                if (before != nullptr && row[0] == before[3 * x] && row[1] == before[3 * x + 1] &&
                    row[2] == before[3 * x + 2])
                    continue;
                enc.image->SetRGBFTValue(x, y, row[0] / 255.0f, row[1] / 255.0f, row[2] / 255.0f,
                                         0.0f, 0.0f);
            }
        }
        enc.last.swap(rgb);
        pov_base::Image::WriteOptions options;
        options.bpcc = 8;
        options.compress = rle ? 1 : 0;
        // With a neutral working gamma TranscodingGammaCurve::Get gives the encoding curve as
        // it is: the one that keeps the values and records the file's gamma.
        options.workingGamma = pov_base::NeutralGammaCurve::Get();
        options.encodingGamma = enc.curve;
        options.dither = pov_base::GetNoOpDitherHandler();
        // Room for the worst run-length encoding (a count byte per pixel) and the footer.
        enc.file.resize(row_bytes * size_t(height) * 4 / 3 + size_t(height) + 4096);
        MemoryOStream stream(enc.file);
        pov_base::Targa::Write(&stream, enc.image.get(), options);
        if (!stream.finish(size)) {
            err = "cannot encode Targa into memory";
            return false;
        }
        return true;
    } catch (const std::exception &e) {
        err = std::string("POV-Ray's Targa writer: ") + e.what();
        return false;
    }
}

// The frame of width x height pixels whose values (3 floats a pixel, rows top first) a
// renderer's writer would quantise, dithered as d says into rgb (3 bytes a pixel): the values
// go into an image as they are, and every pixel is encoded in raster order, as
// ImageProcessing::WriteImage's writers do, through the curve and the dither handler they
// would use. False with err.
bool dither_frame(int width, int height, const fc::Diffusion &d, const std::vector<float> &values,
                  std::vector<unsigned char> &rgb, std::string &err)
{
    // The memo of encoded pixels keys a pixel by its own bits, and a dithered one depends on
    // its neighbours: off meanwhile (it would only forget the Targa writer's image for this).
    povrayfc::EncodeMemo::SetEnabled(false);
    try {
        std::unique_ptr<pov_base::Image> image(
            pov_base::Image::Create(width, height, pov_base::Image::RGBFT_Float));
        const float *v = values.data();
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++, v += 3)
                image->SetRGBFTValue(x, y, v[0], v[1], v[2], 0.0f, 0.0f);
        pov_base::GammaCurvePtr encoding = pov_base::GetGammaCurve(d.file_gamma_type, d.file_gamma);
        pov_base::GammaCurvePtr working =
            pov_base::GetGammaCurve(d.working_gamma_type, d.working_gamma);
        pov_base::GammaCurvePtr gamma = pov_base::TranscodingGammaCurve::Get(
            working, encoding ? encoding : pov_base::SRGBGammaCurve::Get());
        pov_base::DitherHandlerPtr dither = pov_base::GetDitherHandler(d.method, width);
        unsigned char *out = rgb.data();
        for (int y = 0; y < height; y++) {
            for (int x = 0; x < width; x++) {
                unsigned int r, g, b, a;
                pov_base::GetEncodedRGBAValue(image.get(), x, y, gamma, 255, r, g, b, a, *dither,
                                              false);
                *out++ = (unsigned char)r;
                *out++ = (unsigned char)g;
                *out++ = (unsigned char)b;
            }
        }
    } catch (const std::exception &e) {
        err = std::string("POV-Ray's dithering: ") + e.what();
    }
    povrayfc::EncodeMemo::SetEnabled(true);
    return err.empty();
}

} // namespace

int main(int argc, char **argv)
{
    if (argc != 1) {
        fprintf(stderr, "fc-image-writer: takes no arguments; fc-master runs it (requests on "
                        "descriptor 3, replies on 4)\n");
        return 2;
    }
    std::vector<unsigned char> rgb;
    std::vector<float> values;
    Encoder encoder;
    povrayfc::EncodeMemo::SetEnabled(true);
    for (;;) {
        fc_image_writer::Request req;
        bool eof = false;
        if (!read_fully(kRequests, &req, sizeof req, eof)) {
            if (eof)
                return 0;
            fprintf(stderr, "fc-image-writer: cannot read a request on descriptor %d: %s\n",
                    kRequests, errno ? strerror(errno) : "cut short");
            return 1;
        }
        if (req.magic != kRequestMagic || req.width <= 0 || req.height <= 0 ||
            req.width > kMaxSide || req.height > kMaxSide ||
            (req.kind != fc_image_writer::kEncodeTarga && req.kind != fc_image_writer::kDither)) {
            fprintf(stderr, "fc-image-writer: malformed request\n");
            return 1;
        }
        const size_t samples = size_t(req.width) * size_t(req.height) * 3;
        std::string err;
        bool ok;
        const char *answer;
        size_t size = 0;
        if (req.kind == fc_image_writer::kDither) {
            values.resize(samples);
            if (!read_fully(kRequests, values.data(), samples * sizeof(float), eof)) {
                fprintf(stderr, "fc-image-writer: request cut short\n");
                return 1;
            }
            rgb.resize(samples);
            ok = dither_frame(req.width, req.height, req.diffusion, values, rgb, err);
            answer = reinterpret_cast<const char *>(rgb.data());
            size = samples;
        } else {
            rgb.resize(samples);
            if (!read_fully(kRequests, rgb.data(), rgb.size(), eof)) {
                fprintf(stderr, "fc-image-writer: request cut short\n");
                return 1;
            }
            ok = encode_targa(encoder, req.width, req.height, req.rle != 0, req.file_gamma, rgb,
                              size, err);
            answer = encoder.file.data();
        }
        if (!(ok ? reply(1, answer, size) : reply(0, err.data(), err.size())))
            return 1;
    }
}
