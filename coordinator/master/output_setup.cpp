// output_setup.cpp - manifest, resume and room in the output directory (see output_setup.h).
#include "output_setup.h"

#include <cstdio>
#include <map>

#include "files.h"
#include "hashes.h"
#include "text.h"

namespace fc {

Manifest make_manifest(const RenderPlan &plan)
{
    static const char *const kHarmless[] = {
        "Create_Ini", "Frame_Channel", "Frame_Control", "Display", "Display_Gamma",
        "Pause_When_Done", "Verbose", "Work_Threads", "Subset_Start_Frame", "Subset_End_Frame",
        "Output_File_Name", "Input_File_Name", "Test_Abort", "Test_Abort_Count", "Draw_Vistas",
        "Preview_Start_Size", "Preview_End_Size", "All_Console", "All_File", "Debug_Console",
        "Debug_File", "Fatal_Console", "Fatal_File", "Render_Console", "Render_File",
        "Statistic_Console", "Statistic_File", "Warning_Console", "Warning_File",
        "Frame_Coherence", "Frame_Coherence_Grid", "Frame_Coherence_Stats",
        "Frame_Coherence_Mask", "Pre_Scene_Command", "Pre_Frame_Command", "Post_Frame_Command",
        "Post_Scene_Command", "User_Abort_Command", "Fatal_Error_Command", "Pre_Scene_Return",
        "Pre_Frame_Return", "Post_Frame_Return", "Post_Scene_Return", "User_Abort_Return",
        "Fatal_Error_Return"};
    Manifest m;
    m["renderer"] = plan.scene.banner.empty() ? plan.renderer : plan.scene.banner;
    m["scene"] = plan.scene_path;
    for (auto &kv : plan.resolved) {
        bool harmless = false;
        for (const char *h : kHarmless)
            harmless = harmless || kv.first == h;
        if (!harmless)
            m["option " + kv.first] = kv.second;
    }
    return m;
}

FrameInputs scene_inputs(const RenderPlan &plan, InputHashes &hashes)
{
    FrameInputs in;
    FrameInputs::File scene;
    scene.path = plan.scene_path;
    in.files.push_back(scene);
    hashes.fill(in);
    return in;
}

namespace {

// The manifest key of the scene file's contents in records of earlier versions, before the
// contents of every file a frame read were recorded with the frame.
const char *const kLegacySceneContents = "scene contents";

// Why a frame whose file is complete and correct is not kept: its inputs are not as they were
// (empty: they are).
std::string inputs_changed(const FrameFiles &files, const OutputDir &dir, int index,
                           const RenderPlan &plan, const std::string &legacy, InputHashes &hashes)
{
    FrameInputs recorded;
    if (dir.recorded_inputs(base_name(files.final_path(index)), recorded)) {
        if (!recorded.known)
            return "what it read could not be recorded when it was rendered";
        std::vector<std::string> changed = hashes.changed(recorded);
        if (changed.empty())
            return "";
        std::string what = changed[0];
        if (changed.size() > 1)
            what += strf(" and %zu more", changed.size() - 1);
        return "its inputs changed: " + what;
    }
    // An earlier version recorded only the scene's contents, in the manifest.
    std::string text, err;
    if (!legacy.empty() && read_text(plan.scene_path, text, err) &&
        legacy == strf("%016llx", (unsigned long long)hash_bytes(text.data(), text.size())))
        return "";
    return "its inputs changed: " + plan.scene_path;
}

// Which frames the output directory already holds, complete and correct, from the same inputs.
bool resume_frames(const Options &opt, const RenderPlan &plan, const std::string &outdir,
                   bool fresh, bool adopt, const std::string &legacy, FrameBook &book,
                   Preview &preview, RunStats &stats, InputHashes &hashes,
                   std::vector<bool> &replace)
{
    FrameFiles &files = book.files();
    std::vector<std::string> damaged;
    std::map<std::string, int> changed;     // why -> frames
    int adopted = 0;
    for (int i = 0; i < book.count(); i++) {
        std::string path = files.final_path(i);
        if (!file_exists(path))
            continue;
        std::string why;
        std::vector<uint8_t> pixels;
        if (fresh || !files.verify(i, adopt, why, pixels)) {
            replace[size_t(i)] = true;
            if (!fresh)
                damaged.push_back(base_name(path) + " again: " + why);
            continue;
        }
        if (!adopt) {
            why = inputs_changed(files, files.dir(), i, plan, legacy, hashes);
            if (!why.empty()) {
                replace[size_t(i)] = true;
                changed[why]++;
                continue;
            }
        }
        book.resumed(i);
        stats.frame_resumed(i);
        if (adopt) {
            // Made without a record: from the scene as it is now.
            std::string err;
            if (!files.dir().record(base_name(path), FrameFiles::pixels_hash(pixels),
                                    scene_inputs(plan, hashes), err)) {
                fprintf(stderr, "fc-master: %s\n", err.c_str());
                return false;
            }
            adopted++;
        }
        preview.add(i, pixels);
    }
    for (auto &kv : changed)
        fprintf(stderr, "fc-master: rendering %d frame(s) again: %s\n", kv.second,
                kv.first.c_str());
    for (size_t k = 0; k < damaged.size() && k < 5; k++)
        fprintf(stderr, "fc-master: warning: rendering %s\n", damaged[k].c_str());
    if (damaged.size() > 5)
        fprintf(stderr, "fc-master: warning: ... and %zu more frame(s) that are not complete "
                        "and correct\n", damaged.size() - 5);
    if (adopted > 0 && !opt.quiet)
        fprintf(stderr, "fc-master: keeping %d frame(s) already in %s (complete, but made without "
                        "fc-master's record of the run; --force renders them again)\n",
                adopted, outdir.c_str());
    return true;
}

// Before anything renders: room for the frames still to write, at their encoded size.
bool check_space(const std::string &outdir, const RenderPlan &plan, FrameEncoder &encoder,
                 const FrameBook &book, Preview &preview, const std::vector<bool> &replace)
{
    int todo = 0, replaced = 0;
    for (int i = 0; i < book.count(); i++) {
        if (book.state(i) == FrameBook::State::Resumed)
            continue;
        todo++;
        replaced += replace[size_t(i)] ? 1 : 0;
    }
    if (todo == 0)
        return true;
    unsigned long long avail = 0;
    std::string err;
    if (!free_bytes(outdir, avail, err)) {
        fprintf(stderr, "fc-master: output directory: %s\n", err.c_str());
        return false;
    }
    const int width = plan.scene.width, height = plan.scene.height;
    // A frame that replaces one already there reuses its space; one temporary file at a time.
    double frames_needing_room = double(todo - replaced) + 1;
    // With room for the largest a frame can be, the exact size is not needed.
    if (double(avail) >= double(encoder.frame_bytes_bound(width, height)) * frames_needing_room +
                            preview.max_bytes())
        return true;
    bool exact = false;
    double per = double(encoder.frame_bytes(width, height, exact));
    double need = per * frames_needing_room;
    if (double(avail) >= need + preview.max_bytes())
        return true;
    if (double(avail) >= need) {
        // The frames come first.
        fprintf(stderr, "fc-master: warning: no room for the preview in %s (it needs up to %s "
                        "more): turned off\n", outdir.c_str(),
                human_bytes(preview.max_bytes()).c_str());
        preview.stop();
        return true;
    }
    std::string what = strf("%d frame(s) of %s%s need %s, %s is free", todo,
                            exact ? "" : "up to ", human_bytes(per).c_str(),
                            human_bytes(need).c_str(), human_bytes(double(avail)).c_str());
    if (exact || double(avail) < per) {
        fprintf(stderr, "fc-master: not enough space in %s: %s\n", outdir.c_str(), what.c_str());
        return false;
    }
    fprintf(stderr, "fc-master: warning: %s may run out of space: %s (uncompressed; %s frames "
                    "are usually smaller)\n", outdir.c_str(), what.c_str(),
            plan.format.name.c_str());
    return true;
}

} // namespace

bool prepare_output(const Options &opt, const RenderPlan &plan, OutputDir &dir,
                    FrameEncoder &encoder, FrameBook &book, Preview &preview, RunStats &stats,
                    InputHashes &hashes)
{
    const std::string &outdir = dir.path();
    // Frames of another render (scene, options or renderer changed) must not be mixed in.
    // The scene's contents are no longer the manifest's: every frame records its inputs.
    Manifest now = make_manifest(plan);
    std::vector<std::string> diffs;
    if (dir.has_previous())
        for (const std::string &d : dir.differences(now))
            if (!starts_with(d, std::string(kLegacySceneContents) + " is gone"))
                diffs.push_back(d);
    int present = 0;
    for (int i = 0; i < book.count(); i++)
        present += file_exists(book.files().final_path(i)) ? 1 : 0;
    if (!diffs.empty() && present > 0 && !opt.force) {
        std::string list;
        for (size_t k = 0; k < diffs.size() && k < 6; k++)
            list += "  " + diffs[k] + "\n";
        if (diffs.size() > 6)
            list += strf("  ... and %zu more\n", diffs.size() - 6);
        fprintf(stderr, "fc-master: the %d frame(s) in %s were rendered with other settings:\n%s"
                        "fc-master: use --force to render every frame again (each replaced as it "
                        "completes), or another output directory\n",
                present, outdir.c_str(), list.c_str());
        return false;
    }
    bool fresh = opt.force || !diffs.empty();
    // Frames in a directory without a record (written by POV-Ray itself, or by an older
    // fc-master) are kept when they decode completely; with a record, only recorded ones.
    bool adopt = !dir.has_previous() && !fresh;
    auto old = dir.previous().find(kLegacySceneContents);
    std::string legacy = old == dir.previous().end() ? "" : old->second;
    std::string err;
    if (!dir.start_run(now, fresh, err)) {
        fprintf(stderr, "fc-master: output directory %s is not writable: %s\n", outdir.c_str(),
                err.c_str());
        return false;
    }
    std::vector<bool> replace(size_t(book.count()), false);
    return resume_frames(opt, plan, outdir, fresh, adopt, legacy, book, preview, stats, hashes,
                         replace) &&
           check_space(outdir, plan, encoder, book, preview, replace);
}

} // namespace fc
