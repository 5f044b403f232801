// povray_probe.h - what fc-master learns from POV-Ray 3.7 before anything renders: the
// resolved options, and the names of the output files.
//
// The master does not re-implement POV-Ray's option and INI processing (default povray.ini,
// Include_INI, sections, ... ). It asks POV-Ray itself: it runs the renderer once with the
// user's options plus an Include_Header that stops the parser at its first token (#error).
// POV-Ray prints its resolved options (resolution, render area, animation frames and clock,
// output file name) before parsing, so the probe learns them exactly as a real render would
// use them, renders nothing and writes no file. See probe_scene().
#pragma once

#include <map>
#include <string>
#include <vector>

#include "protocol.h"

namespace fc {

// Frame coherence: the INI option the master appends unless --no-fc.
extern const char *const kFrameCoherenceOption;    // "Frame_Coherence=on"

struct SceneInfo {
    int width = 0, height = 0;
    Rect area;                      // render area (+SC/+EC/+SR/+ER), 0-based half-open
    bool animated = false;
    int initial_frame = 0, final_frame = 0, frame_step = 1;
    bool cyclic = false;
    int first_frame = 0;            // first frame of the subset (set_frames)
    std::vector<int> frames;        // frames to render (subset, step applied); {0} for a still
    std::string output_name;        // POV-Ray's output file name for the first frame
    std::string stem;               // output_name without frame number and extension
    std::string ext;                // the extension (".tga", ".png", ".exr")
    int digits = 0;                 // frame number digits in names (0 for a still)
    std::string banner;             // POV-Ray's version line (identifies the renderer)
    bool shellouts_permitted = false;   // povray.conf allows shell-out commands
};

// Run `renderer options... -D -UA +HI<probe.inc>` in cwd (tmpdir holds the probe include, it
// must be readable under POV-Ray's I/O restrictions, e.g. below /tmp), with the user's
// shell-outs replaced (the probe must not run them) and a harmless pre-scene command that
// tells whether povray.conf allows shell-outs. On success fills info; on failure err holds
// POV-Ray's own error lines. Fills all but the names and frames (split_output_name, set_frames).
bool probe_scene(const std::string &renderer, const std::vector<std::string> &options,
                 const std::string &cwd, const std::string &tmpdir, double timeout,
                 SceneInfo &info, std::string &err);

// When POV-Ray says only "Failed to parse command-line option": which of the user's options it
// was (a file named that is not there, or a switch that fails alone), in err. False when none
// can be told.
bool find_bad_option(const std::string &renderer, const std::vector<std::string> &options,
                     const std::string &cwd, double timeout, std::string &err);

// POV-Ray's resolved options as its Create_Ini writes them (key -> value, quotes removed):
// runs `renderer options... +GI<ini> Frame_Channel=<a path that cannot be opened>`, which
// writes the INI file and stops before anything runs (the frame channel opens first).
// A renderer without the frame channel writes none and is refused here.
typedef std::map<std::string, std::string> ResolvedOptions;

// A resolved option's value, or fallback when Create_Ini left it out (it writes only the
// options that are not at their defaults).
std::string resolved_value(const ResolvedOptions &ini, const char *key, const char *fallback);

// Whether an INI switch's value is on (POV-Ray takes on, true, yes and 1, in any case).
bool option_is_on(const std::string &value);
bool probe_resolved_options(const std::string &renderer, const std::vector<std::string> &options,
                            const std::string &cwd, const std::string &tmpdir, double timeout,
                            ResolvedOptions &out, std::string &err);

// From the first frame's output name and the format's extension: stem and digits (or a
// still's single frame). False with err when the name does not fit.
bool split_output_name(SceneInfo &info, const std::string &ext, std::string &err);

// The frames of an animation: from the subset's start to its end, as AnimationProcessing
// computes them from the resolved options (Initial_Frame, Subset_Start_Frame and
// Subset_End_Frame as frames or fractions of the animation, Final_Frame, Cyclic_Animation),
// every Frame_Step; sets info.first_frame. POV-Ray's console may not print "Rendering frame
// k of n" before a short run ends, and a run once started at frame 2 from the number in its
// first output name, so neither is read from there.
bool set_frames(SceneInfo &info, const ResolvedOptions &ini, std::string &err);

// Run argv to completion (or timeout) in cwd, collecting its output lines and wait status.
bool run_collect(const std::vector<std::string> &argv, const std::string &cwd, double timeout,
                 std::vector<std::string> &lines, int &status, std::string &err);

// Output file name of frame (POV-Ray's scheme: stem + frame zero-padded to digits + ext; a
// still image has no number).
std::string frame_file_name(const std::string &stem, int digits, int frame,
                            const std::string &ext);

// Digits POV-Ray uses for frame numbers: those of the final frame (+1 when cyclic).
int frame_digits(int final_frame, bool cyclic);

} // namespace fc
