// shellout.h - the user's Pre/Post_Scene and Pre/Post_Frame commands, run by fc-master as one
// POV-Ray process would run them: the scene commands once, the frame commands once per frame
// (Pre_Frame before the frame's first job is handed out, Post_Frame after the frame is
// written). The slaves' renderers run none (renderer.cpp sets them empty).
//
// The commands and their return actions are POV-Ray's own, read from the INI file POV-Ray
// writes for the user's options (Create_Ini); whether shell-outs are allowed at all is
// asked of POV-Ray too (povray.conf's [Shellout Security]; Debian forbids them). As in
// POV-Ray, a forbidden command counts as one that failed (exit status 1), and a failed
// command triggers its return action: quit (stop, exit status 0), user abort or fatal (stop,
// exit status 1), skip this frame, skip all remaining frames; ignore is the default.
// Parameters expand %o (output file), %s (scene name), %n (frame), %k (clock, %.6f),
// %w, %h (image size) and %% as in POV-Ray; the command runs through /bin/sh.
#pragma once

#include <string>
#include <vector>

#include "povray_probe.h"

namespace fc {

struct ShelloutResult {
    enum Action { Continue, SkipFrame, SkipAll, Quit, Fatal } action = Continue;
    std::string message;        // why the render stops or skips
    std::string notice;         // POV-Ray's line for a prohibited command (the first time)
};

class Shellouts {
public:
    enum Event { PreScene, PreFrame, PostFrame, PostScene, kEvents };

    struct Command {
        std::string command;    // as POV-Ray stores it (program and parameters); empty = none
        char action = 'i';      // i, s, a, q, u, f
        bool negate = false;    // '-' or '!' before the action
    };

    Command commands[kEvents];
    bool permitted = false;     // povray.conf allows shell-outs
    mutable bool told[kEvents] = {};    // POV-Ray's line on a prohibited command was shown
    std::string scene;          // scene name without path or extension (%s)
    int width = 0, height = 0;
    double initial_clock = 0, clock_delta = 0;
    int initial_frame = 0;

    bool any() const;

    // Run the command of event for frame (output: that frame's file, %o).
    ShelloutResult run(Event event, int frame, const std::string &output) const;

    // Expand POV-Ray's % parameters.
    std::string expand(const std::string &command, int frame, const std::string &output) const;
};

// The user's shell-out commands and what %k needs, from POV-Ray's resolved options
// (probe_resolved_options).
void read_shellouts(const ResolvedOptions &ini, Shellouts &out);

} // namespace fc
