// assembly.cpp - frame assembly and output through OpenImageIO (see assembly.h).
#include "assembly.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "durable_write.h"
#include "files.h"
#include "frame_record.h"
#include "hashes.h"
#include "image_codec.h"
#include "povray_probe.h"
#include "text.h"

namespace fc {

FrameAssembly::FrameAssembly(OutputDir &dir, const OutputFormat &format, const std::string &stem,
                             int digits, int width, int height, const std::vector<int> &frames)
    : dir_(dir), format_(format), stem_(stem), digits_(digits), width_(width), height_(height),
      frames_(frames)
{
}

std::string FrameAssembly::final_path(int index) const
{
    return dir_.path() + "/" +
           frame_file_name(stem_, digits_, frames_[size_t(index)], format_.ext);
}

std::string FrameAssembly::temp_path(int index) const
{
    return final_path(index) + ".fc-tmp";
}

size_t FrameAssembly::frame_bytes(bool &exact) const
{
    if (bytes_known_) {
        exact = bytes_exact_;
        return bytes_;
    }
    bytes_ = encoded_size(bytes_exact_);
    bytes_known_ = true;
    exact = bytes_exact_;
    return bytes_;
}

size_t FrameAssembly::raw_bytes() const
{
    return size_t(width_) * size_t(height_) * 3 * pixel_type_bytes(format_.pixels);
}

size_t FrameAssembly::frame_bytes_bound() const
{
    size_t raw = raw_bytes();
    // Run-length Targa at its worst adds a byte per 128 pixels, PNG's stored deflate blocks
    // 5 bytes per 64 KiB and a byte per row; headers and metadata stay far below 64 KiB.
    return raw + raw / 64 + size_t(height_) + (64u << 10);
}

size_t FrameAssembly::encoded_size(bool &exact) const
{
    size_t raw = raw_bytes();
    exact = false;
    if (format_.fixed_size) {
        // Encode a blank frame: an uncompressed format's size does not depend on the pixels.
        std::vector<uint8_t> blank(raw, 0), bytes;
        std::string err;
        if (encode_image(format_.oiio, format_.compression, width_, height_, format_.pixels,
                         blank.data(), bytes, err)) {
            exact = true;
            return bytes.size();
        }
    }
    return frame_bytes_bound();
}

uint64_t FrameAssembly::pixels_hash(const std::vector<uint8_t> &samples, bool words)
{
    return words ? hash_words(samples.data(), samples.size())
                 : hash_bytes(samples.data(), samples.size());
}

bool FrameAssembly::verify(int index, bool adopt, std::string &why,
                           std::vector<uint8_t> &pixels) const
{
    std::string path = final_path(index);
    why.clear();
    if (!file_exists(path))
        return false;
    int w = 0, h = 0, channels = 0;
    std::string err;
    if (!read_image(path, format_.pixels, w, h, channels, pixels, err)) {
        why = "it does not decode completely (" + err + ")";
        return false;
    }
    if (w != width_ || h != height_) {
        why = strf("it is %dx%d, not %dx%d", w, h, width_, height_);
        return false;
    }
    if (format_.fixed_size) {
        // A reader may fill in what a short file lacks; an uncompressed Targa holds at least
        // its 18-byte header and every pixel (whoever wrote it: POV-Ray adds no footer).
        size_t want = 18 + size_t(width_) * size_t(height_) * 3;
        struct stat st;
        if (stat(path.c_str(), &st) == 0 && size_t(st.st_size) < want) {
            why = strf("it is cut short (%lld of at least %zu bytes)", (long long)st.st_size, want);
            return false;
        }
    }
    uint64_t recorded = 0;
    bool words = true;
    if (dir_.recorded(base_name(path), recorded, words)) {
        if (recorded != pixels_hash(pixels, words)) {
            why = "its pixels are not those fc-master wrote";
            return false;
        }
        return true;
    }
    if (!adopt) {
        why = "this run's record does not list it";
        return false;
    }
    return true;
}

void FrameAssembly::remove_stale_temps() const
{
    for (size_t i = 0; i < frames_.size(); i++)
        unlink(temp_path(int(i)).c_str());
}

bool FrameAssembly::put(int index, const std::vector<Rect> &rects, const std::vector<char> &keep,
                        const std::string &encoding, const std::vector<uint8_t> &data,
                        std::vector<uint8_t> file, double file_gamma, std::string &err)
{
    size_t pixels = 0;
    for (const Rect &r : rects) {
        if (r.x0 < 0 || r.y0 < 0 || r.x1 > width_ || r.y1 > height_ || r.area() <= 0) {
            err = strf("rectangle %d,%d,%d,%d lies outside the %dx%d image", r.x0, r.y0, r.x1,
                       r.y1, width_, height_);
            return false;
        }
        pixels += size_t(r.area());
    }
    bool floats = encoding == "rgbf";
    bool fits = encoding == format_.encoding || (floats && format_.pixels == PixelType::U8);
    if (!fits) {
        err = "the renderer sent " + encoding + " pixels for " + format_.name + " output (" +
              format_.encoding + " expected): it lacks patch 0030 (frame channel output formats)";
        return false;
    }
    size_t per_pixel = bytes_per_pixel(encoding);
    if (data.size() < pixels * per_pixel || (!floats && data.size() != pixels * per_pixel)) {
        err = strf("%zu bytes of pixels for %zu pixels", data.size(), pixels);
        return false;
    }
    size_t sample = pixel_type_bytes(format_.pixels);
    Pending &p = frames_in_flight_[index];
    if (p.samples.empty())
        p.samples.assign(size_t(width_) * size_t(height_) * 3 * sample, 0);
    // POV-Ray's file stands for the frame only when this one result brought all of it.
    if (rects.size() == 1 && keep[0] && rects[0] == Rect{0, 0, width_, height_})
        p.file = std::move(file);
    else
        p.file.clear();
    if (file_gamma > 0)
        p.file_gamma = file_gamma;
    if (floats && p.values.empty()) {
        p.quantizer.reset(new Quantizer);
        if (!p.quantizer->parse(data.data() + pixels * 12, data.size() - pixels * 12, err))
            return false;
        p.values.assign(size_t(width_) * size_t(height_) * 3, 0.0f);
    }
    size_t off = 0;     // in pixels
    for (size_t k = 0; k < rects.size(); k++) {
        const Rect &r = rects[k];
        size_t row = size_t(r.width());
        for (int y = r.y0; y < r.y1; y++, off += row) {
            if (!keep[k])
                continue;
            size_t dst = size_t(y) * size_t(width_) + size_t(r.x0);    // in pixels
            const uint8_t *src = data.data() + off * per_pixel;
            if (floats) {
                memcpy(&p.values[dst * 3], src, row * 12);
            } else if (encoding == "rgbl") {
                // Linear floats, stored as OpenEXR's half floats.
                std::vector<float> f(row * 3);
                memcpy(f.data(), src, row * 12);
                if (!floats_to_half(f.data(), reinterpret_cast<uint16_t *>(&p.samples[dst * 6]),
                                    row * 3, err))
                    return false;
            } else {
                // rgb8 and rgb16 are the stored samples (little-endian words, as this host).
                memcpy(&p.samples[dst * 3 * sample], src, row * per_pixel);
            }
        }
    }
    return true;
}

bool FrameAssembly::write(int index, std::vector<uint8_t> &samples, bool &disk_full,
                          std::string &err)
{
    disk_full = false;
    auto it = frames_in_flight_.find(index);
    if (it == frames_in_flight_.end()) {
        err = strf("internal error: frame %d has no pixels", frames_[size_t(index)]);
        return false;
    }
    Pending &p = it->second;
    if (!p.values.empty())
        p.quantizer->dither(p.values, width_, height_, p.samples);
    std::vector<uint8_t> bytes;
    if (!p.file.empty())
        bytes.swap(p.file);
    else if (!encode_image(format_.oiio, format_.compression, width_, height_, format_.pixels,
                           p.samples.data(), bytes, err, p.file_gamma))
        return false;
    std::string tmp = temp_path(index), dst = final_path(index);
    if (!write_file_durably(tmp, bytes.data(), bytes.size(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    // Recorded before it gets its name: a master killed in between leaves a record whose
    // file is missing or another (resume renders it again), never a complete frame under its
    // final name that resume would not recognise and render again.
    if (!dir_.record(base_name(dst), pixels_hash(p.samples), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        unlink(tmp.c_str());
        return false;
    }
    // Only a complete file gets the final name (rename replaces a damaged one atomically).
    if (rename(tmp.c_str(), dst.c_str()) != 0) {
        sys_fail(err, "rename " + tmp + " to " + dst);
        unlink(tmp.c_str());
        return false;
    }
    if (!sync_dir(dir_.path(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    samples.swap(p.samples);
    frames_in_flight_.erase(it);
    return true;
}

} // namespace fc
