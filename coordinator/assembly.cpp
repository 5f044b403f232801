// assembly.cpp - frame assembly and Targa output through OpenImageIO.
#include "assembly.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "image_io.h"
#include "povray.h"
#include "util.h"

namespace fc {

FrameAssembly::FrameAssembly(const std::string &dir, const std::string &stem, int digits,
                             int width, int height, const std::vector<int> &frames)
    : dir_(dir), stem_(stem), digits_(digits), width_(width), height_(height), frames_(frames)
{
}

std::string FrameAssembly::final_path(int index) const
{
    return dir_ + "/" + frame_file_name(stem_, digits_, frames_[size_t(index)]);
}

std::string FrameAssembly::temp_path(int index) const
{
    return final_path(index) + ".fc-tmp";
}

bool FrameAssembly::exists_complete(int index) const
{
    std::string path = final_path(index);
    if (!file_exists(path))
        return false;
    int w = 0, h = 0, channels = 0;
    return image_size(path, w, h, channels) && w == width_ && h == height_ && channels >= 3;
}

void FrameAssembly::remove_stale_temps() const
{
    for (size_t i = 0; i < frames_.size(); i++)
        unlink(temp_path(int(i)).c_str());
}

bool FrameAssembly::put(int index, const std::vector<Rect> &rects, const std::vector<char> &keep,
                        const std::string &encoding, const std::vector<uint8_t> &data,
                        std::string &err)
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
    if (!floats && encoding != "rgb8") {
        err = "unknown pixel encoding '" + encoding + "'";
        return false;
    }
    if (data.size() < pixels * (floats ? 12 : 3) || (!floats && data.size() != pixels * 3)) {
        err = strf("%zu bytes of pixels for %zu pixels", data.size(), pixels);
        return false;
    }
    Pending &p = frames_in_flight_[index];
    if (p.rgb.empty())
        p.rgb.assign(size_t(width_) * size_t(height_) * 3, 0);
    if (floats && p.values.empty()) {
        p.quantizer.reset(new Quantizer);
        if (!p.quantizer->parse(data.data() + pixels * 12, data.size() - pixels * 12, err))
            return false;
        p.values.assign(size_t(width_) * size_t(height_) * 3, 0.0f);
    }
    size_t off = 0;
    for (size_t k = 0; k < rects.size(); k++) {
        const Rect &r = rects[k];
        size_t row = size_t(r.width()) * 3;
        for (int y = r.y0; y < r.y1; y++) {
            size_t dst = (size_t(y) * size_t(width_) + size_t(r.x0)) * 3;
            if (keep[k]) {
                if (floats)
                    memcpy(&p.values[dst], data.data() + off * 4, row * 4);
                else
                    memcpy(&p.rgb[dst], data.data() + off, row);
            }
            off += row;
        }
    }
    return true;
}

bool FrameAssembly::write(int index, std::string &err)
{
    auto it = frames_in_flight_.find(index);
    if (it == frames_in_flight_.end()) {
        err = strf("internal error: frame %d has no pixels", frames_[size_t(index)]);
        return false;
    }
    Pending &p = it->second;
    if (!p.values.empty())
        p.quantizer->dither(p.values, width_, height_, p.rgb);
    std::string tmp = temp_path(index), dst = final_path(index);
    if (!write_targa(tmp, width_, height_, p.rgb.data(), err)) {
        unlink(tmp.c_str());
        return false;
    }
    // Data on disk before the name appears: a frame under its final name is complete.
    int fd = open(tmp.c_str(), O_RDONLY);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
    if (rename(tmp.c_str(), dst.c_str()) != 0) {
        sys_fail(err, "rename " + tmp + " to " + dst);
        unlink(tmp.c_str());
        return false;
    }
    frames_in_flight_.erase(it);
    return true;
}

} // namespace fc
