// output_setup.h - the output directory before anything renders: frames of another render are
// not mixed in (the manifest: scene, options, renderer), frames already there complete and
// correct, whose inputs are as they were, are kept (resume), and there is room for the others.
#pragma once

#include "command_line.h"
#include "frame_book.h"
#include "output_dir.h"
#include "preview.h"
#include "render_plan.h"
#include "run_stats.h"

namespace fc {

// What makes every frame what it is, for the manifest: the renderer, the scene file's name, and
// POV-Ray's resolved options except those that cannot change a pixel (display, console,
// threads, which frames of the animation this run renders). The contents of the files a frame
// read are its inputs (frame_inputs.h), recorded per frame.
Manifest make_manifest(const RenderPlan &plan);

// A frame's inputs when the renderer reports none: the scene file alone, hashed now.
FrameInputs scene_inputs(const RenderPlan &plan, InputHashes &hashes);

// Compare the manifest with the directory's, start the run's record, keep the frames already
// there (each marked resumed in the book and the statistics, and shown in the preview) and
// check the room for the rest. Prints what it refuses or warns about; false when the render
// must not start.
bool prepare_output(const Options &opt, const RenderPlan &plan, OutputDir &dir,
                    FrameEncoder &encoder, FrameBook &book, Preview &preview, RunStats &stats,
                    InputHashes &hashes);

} // namespace fc
