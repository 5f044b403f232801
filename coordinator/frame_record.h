// frame_record.h - the records povray-fc writes to its frame channel, and the lines its frame
// control reads (patches 0020 and 0021; the formats are described in coordinator/README.md).
//
// A record is one ASCII header line, then binary pixels:
//   FCFRAME 1 frame=N rays=R parse=S trace=S encoding=rgb8 rects=K x0,y0,x1,y1 ... bytes=B\n
//   <B bytes: per rectangle, rows top to bottom, 3 bytes R,G,B a pixel>
// encoding=rgbf (diffusion dithering, patch 0022) carries 3 little-endian floats a pixel (the
// values the Targa writer quantizes) followed by the quantizer (see dither.h). Patch 0030 adds
// the encodings of other output formats: rgb16 (3 little-endian 16-bit words a pixel, as the
// PNG writer stores 9 to 16 bits) and rgbl (3 little-endian floats a pixel, the linear values
// the OpenEXR writer converts to half); rgb8 also carries PNG's 5 to 8 bits as it stores them.
// Patch 0034: a record of the whole image in Targa or PNG says file=F and carries, after the
// pixels, the F bytes of the file the format's writer makes of the frame (as one POV-Ray
// process would write it). Patch 0039: file_gamma=G, the gamma the format's writer records in
// the file (Targa's extension area), for the frames fc-master assembles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "protocol.h"

namespace fc {

struct FrameRecord {
    int frame = 0;
    double rays = 0;                // -1 when POV-Ray sent no statistics
    double parse_seconds = 0, trace_seconds = 0;
    std::string encoding;           // "rgb8", "rgb16", "rgbl" or "rgbf"
    std::vector<Rect> rects;
    std::vector<uint8_t> data;      // the pixels, as sent
    std::vector<uint8_t> file;      // the frame's image file (whole-image records), or empty
    double file_gamma = 0;          // the gamma its file records (patch 0039; 0: not said)
};

// Incremental reader: feed it the bytes read from the channel, take complete records out.
class FrameRecordReader {
public:
    void feed(const char *bytes, size_t n);
    // Next complete record: 1 = record filled, 0 = need more bytes, -1 = malformed stream
    // (err says why; the stream cannot be resynchronised).
    int next(FrameRecord &record, std::string &err);
    // Bytes received that are not part of a complete record.
    size_t pending() const { return buf_.size() - pos_; }

private:
    std::string buf_;
    size_t pos_ = 0;
};

// Bytes a pixel takes in an encoding (rgbf: without its quantizer); 0 for an unknown one.
size_t bytes_per_pixel(const std::string &encoding);

// Parse one header line (without its newline) into record (all but data and file);
// payload_bytes is the size of the pixels that follow, file_bytes that of the file after them.
// Returns false with err on a malformed header.
bool parse_record_header(const std::string &line, FrameRecord &record, size_t &payload_bytes,
                         size_t &file_bytes, std::string &err);

// The frame-control line that asks the renderer for frame `frame` restricted to rects
// (none = the whole render area), with its newline.
std::string render_control_line(int frame, const std::vector<Rect> &rects);

} // namespace fc
