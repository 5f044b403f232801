// frame_book.cpp - every frame of the run in one place (see frame_book.h).
#include "frame_book.h"

#include <time.h>

#include <algorithm>
#include <cstring>

#include "frame-channel/frame_record.h"
#include "image_codec.h"
#include "image_writer_client.h"
#include "text.h"

namespace fc {

FrameBook::FrameBook(FrameFiles &files, FrameEncoder &encoder, int width, int height,
                     const std::vector<int> &frames, int tiles)
    : files_(files), encoder_(encoder), width_(width), height_(height), frames_(frames),
      cells_(int(frames.size()), tiles), state_(frames.size(), State::ToRender),
      started_(frames.size(), 0), started_at_(frames.size(), 0)
{
    for (size_t i = 0; i < frames.size(); i++)
        index_of_[frames[i]] = int(i);
}

int FrameBook::index_of(int number) const
{
    auto it = index_of_.find(number);
    return it == index_of_.end() ? -1 : it->second;
}

void FrameBook::no_more_work(int index, State state)
{
    cells_.mark_frame(index);
    state_[size_t(index)] = state;
    pixels_.erase(index);
    complete_.erase(index);
    inputs_.erase(index);
}

void FrameBook::resumed(int index)
{
    no_more_work(index, State::Resumed);
    resumed_++;
}

bool FrameBook::start(int index)
{
    if (started_[size_t(index)])
        return false;
    started_[size_t(index)] = 1;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    started_at_[size_t(index)] = double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
    return true;
}

void FrameBook::skip(int index)
{
    no_more_work(index, State::Skipped);
    skipped_++;
}

void FrameBook::give_up(int index, const std::string &why)
{
    if (state_[size_t(index)] == State::GivenUp)
        return;
    no_more_work(index, State::GivenUp);
    given_up_why_[index] = why;
    given_up_++;
}

std::vector<std::pair<int, std::string>> FrameBook::given_up() const
{
    std::vector<std::pair<int, std::string>> out;
    for (auto &kv : given_up_why_)
        out.push_back({frames_[size_t(kv.first)], kv.second});
    return out;
}

bool FrameBook::deliver(int index, FrameResult &r, std::vector<int> &fresh, std::string &err)
{
    fresh.clear();
    std::vector<char> keep(r.tiles.size(), 0);
    for (size_t k = 0; k < r.tiles.size(); k++)
        if (cells_.mark(index, r.tiles[k])) {
            keep[k] = 1;
            fresh.push_back(r.tiles[k]);
        }
    if (fresh.empty())
        return true;    // a copy that came second: nothing new
    state_[size_t(index)] = State::Assembling;
    if (!put(index, r, keep, err))
        return false;
    if (cells_.frame_done(index)) {
        state_[size_t(index)] = State::Complete;
        complete_.insert(index);
    }
    return true;
}

bool FrameBook::put(int index, FrameResult &r, const std::vector<char> &keep,
                    std::string &err)
{
    const OutputFormat &format = files_.format();
    size_t pixels = 0;
    for (const Rect &rect : r.rects) {
        if (rect.x0 < 0 || rect.y0 < 0 || rect.x1 > width_ || rect.y1 > height_ ||
            rect.area() <= 0) {
            err = strf("rectangle %d,%d,%d,%d lies outside the %dx%d image", rect.x0, rect.y0,
                       rect.x1, rect.y1, width_, height_);
            return false;
        }
        pixels += size_t(rect.area());
    }
    const std::string &encoding = r.encoding;
    bool floats = encoding == "rgbf";
    bool fits = encoding == format.encoding || (floats && format.pixels == PixelType::U8);
    if (!fits) {
        err = "the renderer sent " + encoding + " pixels for " + format.name + " output (" +
              format.encoding + " expected): its frame channel predates the output formats";
        return false;
    }
    size_t per_pixel = bytes_per_pixel(encoding);
    const std::vector<uint8_t> &data = r.data;
    if (data.size() < pixels * per_pixel || (!floats && data.size() != pixels * per_pixel)) {
        err = strf("%zu bytes of pixels for %zu pixels", data.size(), pixels);
        return false;
    }
    size_t sample = pixel_type_bytes(format.pixels);
    Pixels &p = pixels_[index];
    if (p.samples.empty())
        p.samples.assign(size_t(width_) * size_t(height_) * 3 * sample, 0);
    // POV-Ray's file stands for the frame only when this one result brought all of it.
    if (r.rects.size() == 1 && keep[0] && r.rects[0] == Rect{0, 0, width_, height_})
        p.file = std::move(r.file);
    else
        p.file.clear();
    if (r.file_gamma > 0)
        p.file_gamma = r.file_gamma;
    if (floats && p.values.empty()) {
        if (!parse_diffusion(data, pixels, p.diffusion, err))
            return false;
        p.values.assign(size_t(width_) * size_t(height_) * 3, 0.0f);
    }
    size_t off = 0;     // in pixels
    for (size_t k = 0; k < r.rects.size(); k++) {
        const Rect &rect = r.rects[k];
        size_t row = size_t(rect.width());
        for (int y = rect.y0; y < rect.y1; y++, off += row) {
            if (!keep[k])
                continue;
            size_t dst = size_t(y) * size_t(width_) + size_t(rect.x0);    // in pixels
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

int FrameBook::next_to_write(bool wait) const
{
    if (complete_.empty())
        return -1;
    if (!wait && complete_.size() <= kFramesWhileLoading && encoder_.waits_for_image_io())
        return -1;
    return *complete_.begin();
}

bool FrameBook::write(int index, std::vector<uint8_t> &samples, bool &disk_full, std::string &err)
{
    disk_full = false;
    auto it = pixels_.find(index);
    if (it == pixels_.end() || !complete_.count(index)) {
        err = strf("internal error: frame %d is not complete", frames_[size_t(index)]);
        return false;
    }
    Pixels &p = it->second;
    if (!p.values.empty() &&
        !writer_dither(width_, height_, p.diffusion, p.values.data(), p.samples, err)) {
        err = "diffusion dithering: " + err;
        return false;
    }
    std::vector<uint8_t> bytes;
    if (!p.file.empty())
        bytes.swap(p.file);
    else if (!encoder_.encode(width_, height_, p.samples.data(), p.file_gamma, bytes, err))
        return false;
    FrameInputs unknown;
    unknown.known = false;
    auto in = inputs_.find(index);
    if (!files_.store(index, bytes, FrameFiles::pixels_hash(p.samples),
                      in == inputs_.end() ? unknown : in->second, disk_full, err))
        return false;
    if (in != inputs_.end())
        inputs_.erase(in);
    samples.swap(p.samples);
    pixels_.erase(it);
    complete_.erase(index);
    state_[size_t(index)] = State::Written;
    written_++;
    return true;
}

} // namespace fc
