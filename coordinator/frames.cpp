// frames.cpp - frame assembly and Targa output through OpenImageIO.
#include "frames.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <OpenImageIO/imageio.h>

#include "povray.h"
#include "util.h"

namespace fc {

FrameStore::FrameStore(const std::string &dir, const std::string &stem, int digits, int width,
                       int height, const std::vector<int> &frames)
    : dir_(dir), stem_(stem), digits_(digits), width_(width), height_(height), frames_(frames)
{
}

std::string FrameStore::final_path(int index) const
{
    return dir_ + "/" + frame_file_name(stem_, digits_, frames_[size_t(index)]);
}

std::string FrameStore::temp_path(int index) const
{
    return final_path(index) + ".fc-tmp";
}

bool FrameStore::exists_complete(int index) const
{
    std::string path = final_path(index);
    if (!file_exists(path))
        return false;
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        return false;
    const OIIO::ImageSpec &spec = in->spec();
    bool ok = spec.width == width_ && spec.height == height_ && spec.nchannels >= 3;
    in->close();
    return ok;
}

void FrameStore::remove_stale_temps() const
{
    for (size_t i = 0; i < frames_.size(); i++)
        unlink(temp_path(int(i)).c_str());
}

void FrameStore::put(int index, const Rect &rect, const std::vector<uint8_t> &pixels)
{
    std::vector<uint8_t> &buf = buffers_[index];
    if (buf.empty())
        buf.assign(size_t(width_) * size_t(height_) * 3, 0);
    size_t row = size_t(rect.width()) * 3;
    for (int y = rect.y0; y < rect.y1; y++)
        memcpy(&buf[(size_t(y) * size_t(width_) + size_t(rect.x0)) * 3],
               &pixels[size_t(y - rect.y0) * row], row);
}

bool FrameStore::write(int index, std::string &err)
{
    auto it = buffers_.find(index);
    if (it == buffers_.end()) {
        err = strf("internal error: frame %d has no pixels", frames_[size_t(index)]);
        return false;
    }
    std::string tmp = temp_path(index), dst = final_path(index);
    auto out = OIIO::ImageOutput::create("tga");
    if (!out) {
        err = "OpenImageIO has no Targa writer: " + OIIO::geterror();
        return false;
    }
    OIIO::ImageSpec spec(width_, height_, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("compression", "none");
    if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, it->second.data()) ||
        !out->close()) {
        err = "writing " + tmp + ": " + out->geterror();
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
    buffers_.erase(it);
    return true;
}

} // namespace fc
