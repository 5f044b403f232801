// frame_record.h - the record a renderer writes on its frame channel for each finished
// frame: the one definition of the format, with its writer (the renderer's frame channel,
// frame_channel.cpp) and its reader (fc-slave). No POV-Ray headers: fc-slave builds it too.
//
// A record is one ASCII header line, then binary data:
//   FCFRAME 1 frame=N rays=R parse=S trace=S encoding=E rects=K x0,y0,x1,y1 ... [file=F]
//     file_gamma=G [reads=R] bytes=B\n                              (one line)
//   <B bytes: the pixels, per rectangle its rows top to bottom>
//   <F bytes: the image file of the whole frame, when the header says file=F>
//   <R bytes: the files the frame's parse read, when the header says reads=R>
// Rectangles are 0-based and half-open, [x0,x1) x [y0,y1) in full-image pixels: those the
// frame control asked for, else the whole image. rays is the frame's "Rays:" statistic
// (-1: none), parse and trace are wall seconds. file_gamma is the gamma the output format's
// writer records in the file (Targa's extension area), so that a frame assembled from tiles
// records what one POV-Ray process's file would. A reader skips fields it does not know.
//
// Encodings, a pixel as the output format's writer stores it:
//   rgb8   3 bytes R,G,B: Targa, and PNG at 5 to 8 bits (replicated into the byte)
//   rgb16  3 little-endian 16-bit words: PNG at 9 to 16 bits (replicated into the word)
//   rgbl   3 native floats, linear and premultiplied: OpenEXR (its writer makes them half)
//   rgbf   3 native floats, the values the writer would quantise, then a Diffusion (below):
//          error diffusion carries each pixel's error into other tiles, so the receiver
//          dithers the assembled frame, with POV-Ray's own dither handler (fc-image-writer)
// A record of the whole image in Targa or PNG also carries the file the format's writer
// makes of the frame (file=F), so a frame rendered whole is stored as it is.
//
// The reads section (reads=R; parse_reads.h collects it) says which files the frame's picture
// depends on, so that fc-master's resume keeps a frame only while they are as they were. It
// is lines of text, each "F<TAB>path<LF>", "A<TAB>path<LF>" or "U<TAB>path<LF>":
//   F  a file the frame's parse opened and read: the scene, an include, a macro's file, an
//      image map, a density file, a font, a file #fopen'd for #read (POV-Ray's Locate_File);
//   A  a path the parse's search looked at and found no file at: every candidate tried by a
//      lookup that found nothing (file_exists, a missing include) and those tried before the
//      one a lookup found (a file created there later would be found instead); each name with
//      each extension of its type, in the current directory and then in each library path
//      (FileMessageHandler::FindFilePath);
//   U  a path of either kind with a line break in it, which a line cannot carry (its breaks
//      are spaces here): the frame's inputs cannot be known, and a resume renders it again.
// Paths are as POV-Ray formed them: relative ones are relative to the renderer's directory.
// Each line once, in the order first met; only this frame's parse (from its start to its
// record). No section (or R = 0): the renderer reported nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fc {

// A rectangle of the image: [x0,x1) x [y0,y1), 0-based.
struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    long area() const { return long(width()) * height(); }
    bool operator==(const Rect &o) const
    {
        return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
    }
};

struct FrameRecord {
    int frame = 0;
    double rays = 0;                // -1 when POV-Ray sent no statistics
    double parse_seconds = 0, trace_seconds = 0;
    std::string encoding;           // "rgb8", "rgb16", "rgbl" or "rgbf"
    std::vector<Rect> rects;
    std::vector<uint8_t> data;      // the pixels, as sent (rgbf: with its Diffusion)
    std::vector<uint8_t> file;      // the frame's image file (whole-image records), or empty
    double file_gamma = 0;          // the gamma its file records (0: not said)
    std::string reads;              // the reads section: "F<TAB>path" / "A<TAB>path" lines
};

// The sizes of what follows a record's header line, in that order.
struct RecordSizes {
    size_t pixels = 0;              // bytes=B
    size_t file = 0;                // file=F
    size_t reads = 0;               // reads=R
};

// What an rgbf record's receiver dithers with, after the pixels (native byte order):
// POV-Ray's dither method (kPOVList_DitherMethod_*: 1 = d1, 2 = d2, 3 = fs) and the two
// gamma curves of POV-Ray's options (type kPOVList_GammaType_*, and value) between which
// the writer encodes: working gamma to file gamma.
struct Diffusion {
    int32_t method = 0;
    int32_t working_gamma_type = 0;
    float working_gamma = 0;
    int32_t file_gamma_type = 0;
    float file_gamma = 0;
};

// The methods that diffuse a pixel's error into its neighbours.
bool is_diffusion_method(int method);

// Bytes a pixel takes in an encoding (rgbf: without its Diffusion); 0 for an unknown one.
size_t bytes_per_pixel(const std::string &encoding);

// The header line of record (with its newline), for its data, file and reads as they are.
std::string record_header(const FrameRecord &record);

// Parse one header line (without its newline) into record (all but data, file and reads) and
// the sizes of what follows it. Returns false with err on a malformed header.
bool parse_record_header(const std::string &line, FrameRecord &record, RecordSizes &sizes,
                         std::string &err);

// Append d to an rgbf record's pixels; read it back from the data of a record of `pixels`
// pixels (false with err when it is missing or names no diffusion method).
void append_diffusion(const Diffusion &d, std::vector<uint8_t> &data);
bool parse_diffusion(const std::vector<uint8_t> &data, size_t pixels, Diffusion &d,
                     std::string &err);

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

} // namespace fc
