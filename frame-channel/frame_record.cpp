// frame_record.cpp - writing and reading frame-channel records (see frame_record.h).
#include "frame-channel/frame_record.h"

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace fc {

namespace {

const size_t kMaxHeader = 1 << 20;      // a header with thousands of rectangles is still small
const size_t kMaxPayload = size_t(1) << 34;
const size_t kMaxReads = size_t(1) << 30;  // lines of paths: a million files are 100 MB

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

std::string field(const char *format, ...) __attribute__((format(printf, 1, 2)));

std::string field(const char *format, ...)
{
    char buf[96];
    va_list args;
    va_start(args, format);
    vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    return buf;
}

} // namespace

bool is_diffusion_method(int method)
{
    return method == 1 || method == 2 || method == 3;
}

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

std::string record_header(const FrameRecord &rec)
{
    std::string header = "FCFRAME 1";
    header += field(" frame=%d rays=%lld", rec.frame, (long long)rec.rays);
    header += field(" parse=%.6f trace=%.6f encoding=%s rects=%u", rec.parse_seconds,
                    rec.trace_seconds, rec.encoding.c_str(), unsigned(rec.rects.size()));
    for (const Rect &r : rec.rects)
        header += field(" %d,%d,%d,%d", r.x0, r.y0, r.x1, r.y1);
    if (!rec.file.empty())
        header += field(" file=%lu", (unsigned long)rec.file.size());
    header += field(" file_gamma=%.9g", rec.file_gamma);
    if (!rec.reads.empty())
        header += field(" reads=%lu", (unsigned long)rec.reads.size());
    header += field(" bytes=%lu\n", (unsigned long)rec.data.size());
    return header;
}

bool parse_record_header(const std::string &line, FrameRecord &rec, RecordSizes &sizes,
                         std::string &err)
{
    sizes = RecordSizes();
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
            sizes.pixels = size_t(v);
            have_bytes = true;
        } else if (key == "file") {
            if (v < 0 || v > double(kMaxPayload)) {
                err = "frame record file size out of range: " + value;
                return false;
            }
            sizes.file = size_t(v);
        } else if (key == "reads") {
            if (v < 0 || v > double(kMaxReads)) {
                err = "frame record reads size out of range: " + value;
                return false;
            }
            sizes.reads = size_t(v);
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
    size_t expected = pixels * per_pixel + (rec.encoding == "rgbf" ? sizeof(Diffusion) : 0);
    if (sizes.pixels != expected) {
        err = "frame record of frame " + std::to_string(rec.frame) + " has " +
              std::to_string(sizes.pixels) + " bytes for " + std::to_string(pixels) + " pixels";
        return false;
    }
    return true;
}

void append_diffusion(const Diffusion &d, std::vector<uint8_t> &data)
{
    const uint8_t *p = reinterpret_cast<const uint8_t *>(&d);
    data.insert(data.end(), p, p + sizeof d);
}

bool parse_diffusion(const std::vector<uint8_t> &data, size_t pixels, Diffusion &d,
                     std::string &err)
{
    size_t at = pixels * bytes_per_pixel("rgbf");
    if (data.size() != at + sizeof d) {
        err = "diffusion dithering record of " + std::to_string(data.size()) + " bytes for " +
              std::to_string(pixels) + " pixels";
        return false;
    }
    memcpy(&d, data.data() + at, sizeof d);
    if (!is_diffusion_method(d.method)) {
        err = "unknown diffusion dithering method " + std::to_string(d.method);
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
    RecordSizes sizes;
    if (!parse_record_header(buf_.substr(pos_, nl - pos_), rec, sizes, err))
        return -1;
    size_t body = sizes.pixels + sizes.file + sizes.reads;
    if (buf_.size() - (nl + 1) < body)
        return 0;
    // Through uint8_t pointers: assigned from the string's char iterators, the bytes were
    // converted one by one instead of copied as a block (a tenth of fc-slave's CPU).
    const uint8_t *start = reinterpret_cast<const uint8_t *>(buf_.data()) + nl + 1;
    rec.data.assign(start, start + sizes.pixels);
    rec.file.assign(start + sizes.pixels, start + sizes.pixels + sizes.file);
    rec.reads.assign(buf_, nl + 1 + sizes.pixels + sizes.file, sizes.reads);
    pos_ = nl + 1 + body;
    return 1;
}

} // namespace fc
