// frame_record.cpp - parsing frame-channel records and writing frame-control lines.
#include "frame_record.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "util.h"

namespace fc {

namespace {

const size_t kMaxHeader = 1 << 20;      // a header with thousands of rectangles is still small
const size_t kMaxPayload = size_t(1) << 34;

bool parse_number(const std::string &s, double &v)
{
    char *end = nullptr;
    v = strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0';
}

bool parse_rect(const std::string &s, Rect &r)
{
    char tail;
    return sscanf(s.c_str(), "%d,%d,%d,%d%c", &r.x0, &r.y0, &r.x1, &r.y1, &tail) == 4 &&
           r.x0 >= 0 && r.y0 >= 0 && r.x1 > r.x0 && r.y1 > r.y0;
}

} // namespace

size_t bytes_per_pixel(const std::string &encoding)
{
    if (encoding == "rgb8")
        return 3;
    if (encoding == "rgb16")
        return 6;
    if (encoding == "rgbf" || encoding == "rgbl")
        return 12;
    return 0;
}

bool parse_record_header(const std::string &line, FrameRecord &rec, size_t &payload_bytes,
                         size_t &file_bytes, std::string &err)
{
    file_bytes = 0;
    std::istringstream words(line);
    std::string magic, version, w;
    if (!(words >> magic >> version) || magic != "FCFRAME" || version != "1") {
        err = "not a frame record: '" + line.substr(0, 80) + "'";
        return false;
    }
    bool have_frame = false, have_bytes = false, have_rects = false;
    rec = FrameRecord();
    while (words >> w) {
        size_t eq = w.find('=');
        if (eq == std::string::npos) {
            err = "frame record field without '=': " + w;
            return false;
        }
        std::string key = w.substr(0, eq), value = w.substr(eq + 1);
        double v = 0;
        if (key == "encoding") {
            rec.encoding = value;
            continue;
        }
        if (!parse_number(value, v)) {
            err = "frame record field " + key + " is not a number: " + value;
            return false;
        }
        if (key == "frame") {
            rec.frame = int(v);
            have_frame = true;
        } else if (key == "rays") {
            rec.rays = v;
        } else if (key == "parse") {
            rec.parse_seconds = v;
        } else if (key == "trace") {
            rec.trace_seconds = v;
        } else if (key == "file_gamma") {
            rec.file_gamma = v;
        } else if (key == "bytes") {
            if (v < 0 || v > double(kMaxPayload)) {
                err = "frame record size out of range: " + value;
                return false;
            }
            payload_bytes = size_t(v);
            have_bytes = true;
        } else if (key == "file") {
            if (v < 0 || v > double(kMaxPayload)) {
                err = "frame record file size out of range: " + value;
                return false;
            }
            file_bytes = size_t(v);
        } else if (key == "rects") {
            int n = int(v);
            for (int i = 0; i < n; i++) {
                Rect r;
                std::string s;
                if (!(words >> s) || !parse_rect(s, r)) {
                    err = "frame record rectangle " + std::to_string(i + 1) + " is malformed";
                    return false;
                }
                rec.rects.push_back(r);
            }
            have_rects = n > 0;
        }
        // Unknown keys are ignored: a newer renderer may say more.
    }
    size_t per_pixel = bytes_per_pixel(rec.encoding);
    if (!have_frame || !have_bytes || !have_rects || per_pixel == 0) {
        err = "frame record lacks frame, rects, bytes or a known encoding: '" +
              line.substr(0, 120) + "'";
        return false;
    }
    size_t pixels = 0;
    for (const Rect &r : rec.rects)
        pixels += size_t(r.area());
    size_t expected = pixels * per_pixel;
    // rgbf is followed by its quantizer table, so it is longer than the pixels.
    if (rec.encoding == "rgbf" ? payload_bytes < expected : payload_bytes != expected) {
        err = strf("frame record of frame %d has %zu bytes for %zu pixels", rec.frame,
                   payload_bytes, pixels);
        return false;
    }
    return true;
}

void FrameRecordReader::feed(const char *bytes, size_t n)
{
    // Drop what was consumed before growing the buffer.
    if (pos_ > 0 && pos_ == buf_.size()) {
        buf_.clear();
        pos_ = 0;
    } else if (pos_ > (1 << 20)) {
        buf_.erase(0, pos_);
        pos_ = 0;
    }
    buf_.append(bytes, n);
}

int FrameRecordReader::next(FrameRecord &rec, std::string &err)
{
    size_t nl = buf_.find('\n', pos_);
    if (nl == std::string::npos) {
        if (buf_.size() - pos_ > kMaxHeader) {
            err = "frame channel: header line too long";
            return -1;
        }
        return 0;
    }
    size_t payload = 0, file = 0;
    if (!parse_record_header(buf_.substr(pos_, nl - pos_), rec, payload, file, err))
        return -1;
    if (buf_.size() - (nl + 1) < payload + file)
        return 0;
    // Through uint8_t pointers: assigned from the string's char iterators, the bytes were
    // converted one by one instead of copied as a block (a tenth of fc-slave's CPU).
    const uint8_t *start = reinterpret_cast<const uint8_t *>(buf_.data()) + nl + 1;
    rec.data.assign(start, start + payload);
    rec.file.assign(start + payload, start + payload + file);
    pos_ = nl + 1 + payload + file;
    return 1;
}

std::string render_control_line(int frame, const std::vector<Rect> &rects)
{
    std::string line = strf("render %d", frame);
    for (const Rect &r : rects)
        line += strf(" %d,%d,%d,%d", r.x0, r.y0, r.x1, r.y1);
    return line + "\n";
}

} // namespace fc
