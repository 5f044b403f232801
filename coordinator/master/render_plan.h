// render_plan.h - what fc-master knows before anything renders: the programs, and what POV-Ray
// itself says the user's options mean (image size, render area, frames, output name and
// format, shell-outs), the tiles, and the options the slaves' renderers get on top of the
// user's. A missing scene or bad option is found here, before any pvmd starts.
#pragma once

#include <string>
#include <vector>

#include "command_line.h"
#include "output_format.h"
#include "povray_probe.h"
#include "shellout.h"

namespace fc {

struct RenderPlan {
    std::string renderer;                   // absolute path of povray-fc
    std::string slave_program;              // absolute path of fc-slave
    std::string cwd;                        // the master's directory (the slaves' too)
    // For the slaves' renderers, after the user's options: the format resolved here (e.g.
    // +FN8), then frame coherence and the render block size.
    std::vector<std::string> format_options;
    std::vector<std::string> extra;
    SceneInfo scene;
    std::string scene_path;                 // the scene file (Input_File_Name), absolute
    ResolvedOptions resolved;               // POV-Ray's resolved options (Create_Ini)
    OutputFormat format;
    std::vector<Rect> tiles;
    Shellouts shellouts;
};

// Find the programs and ask POV-Ray (two probes at once). False with err (POV-Ray's own lines
// when it rejected the scene).
bool make_render_plan(const Options &opt, RenderPlan &plan, std::string &err);

} // namespace fc
