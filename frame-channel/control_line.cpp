// control_line.cpp - writing and reading frame-control lines (see control_line.h).
#include "frame-channel/control_line.h"

#include <cstdio>
#include <sstream>

namespace fc {

std::string render_control_line(int frame, const std::vector<Rect> &rects)
{
    std::string line = "render " + std::to_string(frame);
    for (const Rect &r : rects)
        line += " " + std::to_string(r.x0) + "," + std::to_string(r.y0) + "," +
                std::to_string(r.x1) + "," + std::to_string(r.y1);
    return line + "\n";
}

bool parse_control_line(const std::string &line, ControlLine &control, std::string &err)
{
    control = ControlLine();
    std::istringstream words(line);
    std::string verb;
    if (!(words >> verb))
        return true;
    if (verb == "stop") {
        control.verb = ControlLine::kStop;
        return true;
    }
    if (verb != "render" || !(words >> control.frame)) {
        err = "cannot understand '" + line + "'";
        return false;
    }
    control.verb = ControlLine::kRender;
    std::string word;
    while (words >> word) {
        Rect r;
        char end;
        if (sscanf(word.c_str(), "%d,%d,%d,%d%c", &r.x0, &r.y0, &r.x1, &r.y1, &end) != 4 ||
            r.x0 < 0 || r.y0 < 0 || r.x1 <= r.x0 || r.y1 <= r.y0) {
            err = "bad rectangle '" + word + "' in '" + line + "'";
            return false;
        }
        control.rects.push_back(r);
    }
    return true;
}

} // namespace fc
