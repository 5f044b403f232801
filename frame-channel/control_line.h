// control_line.h - the lines a renderer's frame control reads, one before each frame: the
// one definition of their format, written by fc-slave and read by the renderer's frame
// control (frame_control.cpp). No POV-Ray headers.
//
//   render N [x0,y0,x1,y1 ...]   render frame N; frames before it are skipped unparsed.
//                                With rectangles (0-based, half-open, full-image pixels)
//                                only the render blocks that meet one of them are traced.
//   stop                         end the render successfully (as the end of the file does)
#pragma once

#include <string>
#include <vector>

#include "frame-channel/frame_record.h"

namespace fc {

// The line that asks for frame `frame` restricted to rects (none: the whole render area),
// with its newline.
std::string render_control_line(int frame, const std::vector<Rect> &rects);

struct ControlLine {
    enum Verb { kNone, kRender, kStop } verb = kNone;   // kNone: a blank line
    int frame = 0;
    std::vector<Rect> rects;
};

// Parse one line (without its newline); false with err ("cannot understand 'LINE'", "bad
// rectangle 'R' in 'LINE'") when it is malformed.
bool parse_control_line(const std::string &line, ControlLine &control, std::string &err);

} // namespace fc
