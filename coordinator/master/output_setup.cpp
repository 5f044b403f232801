// output_setup.cpp - manifest, resume and room in the output directory (see output_setup.h).
#include "output_setup.h"

#include <cstdio>

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
    auto in = plan.resolved.find("Input_File_Name");
    std::string scene = in == plan.resolved.end() ? "" : in->second;
    std::string path = !scene.empty() && scene[0] == '/' ? scene : plan.cwd + "/" + scene;
    m["scene"] = absolute_path(path);
    std::string text, err;
    m["scene contents"] = read_text(path, text, err)
                              ? strf("%016llx", (unsigned long long)hash_bytes(text.data(), text.size()))
                              : "(unreadable)";
    for (auto &kv : plan.resolved) {
        bool harmless = false;
        for (const char *h : kHarmless)
            harmless = harmless || kv.first == h;
        if (!harmless)
            m["option " + kv.first] = kv.second;
    }
    return m;
}

namespace {

// Which frames the output directory already holds, complete and correct.
bool resume_frames(const Options &opt, const std::string &outdir, bool fresh, bool adopt,
                   FrameBook &book, Preview &preview, RunStats &stats, std::vector<bool> &replace)
{
    FrameFiles &files = book.files();
    std::vector<std::string> damaged;
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
        book.resumed(i);
        stats.frame_resumed(i);
        if (adopt) {
            std::string err;
            if (!files.dir().record(base_name(path), FrameFiles::pixels_hash(pixels), err)) {
                fprintf(stderr, "fc-master: %s\n", err.c_str());
                return false;
            }
            adopted++;
        }
        preview.add(i, pixels);
    }
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
                    FrameEncoder &encoder, FrameBook &book, Preview &preview, RunStats &stats)
{
    const std::string &outdir = dir.path();
    // Frames of another render (scene, options or renderer changed) must not be mixed in.
    Manifest now = make_manifest(plan);
    std::vector<std::string> diffs;
    if (dir.has_previous())
        diffs = dir.differences(now);
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
    std::string err;
    if (!dir.start_run(now, fresh, err)) {
        fprintf(stderr, "fc-master: output directory %s is not writable: %s\n", outdir.c_str(),
                err.c_str());
        return false;
    }
    std::vector<bool> replace(size_t(book.count()), false);
    return resume_frames(opt, outdir, fresh, adopt, book, preview, stats, replace) &&
           check_space(outdir, plan, encoder, book, preview, replace);
}

} // namespace fc
