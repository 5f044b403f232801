// master_setup.cpp - fc-master before and after the receive loop: find the programs, probe
// the scene, prepare the output (resume), start the virtual machine and the slaves, and write
// the statistics at the end.
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "clock.h"
#include "debug_log.h"
#include "files.h"
#include "hashes.h"
#include "host_info.h"
#include "image_codec.h"
#include "master.h"
#include "render_blocks.h"
#include "temp_dirs.h"
#include "text.h"

namespace fc {

namespace {

std::string absolute(const std::string &path)
{
    char buf[PATH_MAX];
    if (realpath(path.c_str(), buf))
        return buf;
    if (!path.empty() && path[0] == '/')
        return path;
    char cwd[PATH_MAX];
    if (!getcwd(cwd, sizeof cwd))
        return path;
    return std::string(cwd) + "/" + path;
}

} // namespace

HostStat &Master::host_stat(const std::string &name)
{
    HostStat &h = host_stats_[name];
    h.name = name;
    return h;
}

int Master::index_of(int frame) const
{
    auto it = frame_index_.find(frame);
    return it == frame_index_.end() ? -1 : it->second;
}

bool Master::resolve_programs()
{
    std::string here = self_dir();
    if (!opt_.povray.empty()) {
        renderer_ = which(opt_.povray);
        if (renderer_.empty()) {
            fprintf(stderr, "fc-master: renderer %s not found or not executable\n",
                    opt_.povray.c_str());
            return false;
        }
    } else if (const char *env = getenv("FC_POVRAY"); env && *env) {
        renderer_ = which(env);
    } else if (is_executable(here + "/povray-fc")) {
        renderer_ = here + "/povray-fc";
    } else {
        renderer_ = which("povray-fc");
    }
    if (renderer_.empty()) {
        fprintf(stderr, "fc-master: no renderer found (povray-fc); use --povray PATH\n");
        return false;
    }
    renderer_ = absolute(renderer_);

    std::string slave = opt_.slave.empty() ? here + "/fc-slave" : opt_.slave;
    if (slave.find('/') == std::string::npos)
        slave = which(slave).empty() ? slave : which(slave);
    cluster_.slave_prog = absolute(slave);
    if (!is_executable(cluster_.slave_prog)) {
        fprintf(stderr, "fc-master: slave program %s is missing or not executable "
                        "(build it with 'make -C coordinator', or use --slave PATH)\n",
                cluster_.slave_prog.c_str());
        return false;
    }
    char buf[PATH_MAX];
    if (!getcwd(buf, sizeof buf)) {
        perror("fc-master: getcwd");
        return false;
    }
    cwd_ = buf;
    return true;
}

// The output is named like a PNG or OpenEXR file (+Oclk.png): unless the user named a format,
// frames are written in that one, as POV-Ray names PNG frames clk1.png, not clk.png1.tga. The
// resolved options are asked again with PNG put before the user's options: where the answer
// differs from the one with Targa before them, the user named no format. (Asked only here:
// every other output name gives Targa either way, and a start of povray-fc is time on the
// master's host.)
bool Master::choose_format_by_name(ResolvedOptions &ini, double limit, std::string &err)
{
    if (mkdir((tmpdir_ + "/png").c_str(), 0700) != 0) {
        err = "mkdir " + tmpdir_ + "/png: " + strerror(errno);
        return false;
    }
    ResolvedOptions png;
    if (!probe_resolved_options(renderer_, "+FN", opt_.pov, cwd_, tmpdir_ + "/png", limit, png,
                                err))
        return false;
    if (ini["Output_File_Type"] == png["Output_File_Type"])
        return true;
    std::string option = format_from_name(ini);
    ini["Output_File_Type"] = option.substr(2);
    format_options_ = {option};
    scene_ = SceneInfo();
    return probe_scene(renderer_, option, opt_.pov, cwd_, tmpdir_, limit, scene_, err);
}

bool Master::probe()
{
    std::string err;
    remove_stale_dirs("/tmp", "fc-master-");
    if (!make_temp_dir("/tmp", strf("fc-master-%d-", int(getpid())), tmpdir_, err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    // Both questions to POV-Ray at once: each start of povray-fc costs a tenth of a second.
    double limit = std::max(30.0, opt_.timeout);
    std::string scene_err, ini_err;
    bool ini_ok = false;
    ResolvedOptions ini;
    std::thread resolved([&] {
        ini_ok = probe_resolved_options(renderer_, "+FT", opt_.pov, cwd_, tmpdir_, limit, ini,
                                        ini_err);
    });
    // OpenImageIO (262 shared libraries, 0.4 s of CPU; on the master's host out of its
    // slave's time) is needed only for what neither POV-Ray's file of a whole frame (patch
    // 0034) nor fc-image-writer (POV-Ray's Targa writer, for assembled frames) covers: PNG and
    // OpenEXR frames, resumed frames and the preview. Without fc-image-writer a frame or hybrid
    // division needs it for every frame: then it loads while POV-Ray is probed and the slaves
    // start, when the processors are mostly idle; not during the first frames, where it would
    // hold one slave back for the whole run (fc keeps tiles where they are). Not before the
    // thread above: while dlopen() runs, glibc's loader lock stalls every pthread_create.
    bool targa_by_writer = encoded_by_image_writer("targa", PixelType::U8);
    if (opt_.division != Division::Sequence && !targa_by_writer)
        preload_image_io();
    bool scene_ok = probe_scene(renderer_, "+FT", opt_.pov, cwd_, tmpdir_, limit, scene_, scene_err);
    resolved.join();
    err = !scene_ok ? scene_err : ini_err;
    if (scene_ok && ini_ok && format_from_name(ini) != "+FT" &&
        !choose_format_by_name(ini, limit, err))
        ini_ok = false;
    if (scene_ok && ini_ok &&
        (!output_format(ini, format_, err) || !split_output_name(scene_, format_.ext, err) ||
         !set_frames(scene_, ini, err)))
        ini_ok = false;
    if (!scene_ok || !ini_ok) {
        fprintf(stderr, "fc-master: %s", err.c_str());
        if (err.empty() || err.back() != '\n')
            fputc('\n', stderr);
        return false;
    }
    // OpenEXR's half floats are made by OpenImageIO as the frames arrive; assembled PNG
    // frames are encoded by it.
    bool assembled_by_writer = encoded_by_image_writer(format_.oiio, format_.pixels);
    if (format_.pixels == PixelType::Half ||
        (opt_.division != Division::Sequence && !assembled_by_writer))
        preload_image_io();
    // A renderer with the frame channel (the shell-out probe needs it) has frame coherence:
    // the channel's patches come after fc's.
    if (opt_.fc)
        extra_.push_back(kFrameCoherenceOption);
    if (opt_.division != Division::Sequence) {
        // Blocks inside tiles: no block traced by two slaves where the pixels allow it.
        int block = slave_render_block(ini, opt_.tile);
        if (block > 0)
            extra_.push_back(strf("Render_Block_Size=%d", block));
    }
    resolved_ = ini;
    read_shellouts(ini, shellouts_);
    shellouts_.permitted = scene_.shellouts_permitted;
    shellouts_.width = scene_.width;
    shellouts_.height = scene_.height;
    for (size_t i = 0; i < scene_.frames.size(); i++)
        frame_index_[scene_.frames[i]] = int(i);
    if (opt_.division == Division::Sequence)
        tiles_ = {scene_.area};
    else
        tiles_ = make_tiles(scene_.area, opt_.tile);
    return true;
}

// What makes the frames what they are, for the output directory's manifest: the renderer,
// the scene file and its contents, and POV-Ray's resolved options except those that cannot
// change a pixel (display, console, threads, which frames of the animation this run renders).
Manifest Master::manifest() const
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
    m["renderer"] = scene_.banner.empty() ? renderer_ : scene_.banner;
    auto in = resolved_.find("Input_File_Name");
    std::string scene = in == resolved_.end() ? "" : in->second;
    std::string path = !scene.empty() && scene[0] == '/' ? scene : cwd_ + "/" + scene;
    m["scene"] = absolute(path);
    std::string text, err;
    m["scene contents"] = read_text(path, text, err)
                              ? strf("%016llx", (unsigned long long)hash_bytes(text.data(), text.size()))
                              : "(unreadable)";
    for (auto &kv : resolved_) {
        bool harmless = false;
        for (const char *h : kHarmless)
            harmless = harmless || kv.first == h;
        if (!harmless)
            m["option " + kv.first] = kv.second;
    }
    return m;
}

// Resume: which frames the output directory already holds, complete and correct.
bool Master::resume_frames(bool fresh, bool adopt, std::vector<bool> &replace)
{
    std::vector<std::string> damaged;
    int adopted = 0;
    for (size_t i = 0; i < scene_.frames.size(); i++) {
        std::string path = assembly_->final_path(int(i));
        if (!file_exists(path))
            continue;
        std::string why;
        std::vector<uint8_t> pixels;
        if (fresh || !assembly_->verify(int(i), adopt, why, pixels)) {
            replace[i] = true;
            if (!fresh)
                damaged.push_back(base_name(path) + " again: " + why);
            continue;
        }
        frame_stats_[i].resumed = true;
        sched_->mark_frame_done(int(i));
        resumed_++;
        if (adopt) {
            std::string err;
            if (!outdir_obj_.record(base_name(path), FrameAssembly::pixels_hash(pixels), err)) {
                fprintf(stderr, "fc-master: %s\n", err.c_str());
                return false;
            }
            adopted++;
        }
        preview_.add(int(i), pixels);
    }
    for (size_t k = 0; k < damaged.size() && k < 5; k++)
        fprintf(stderr, "fc-master: warning: rendering %s\n", damaged[k].c_str());
    if (damaged.size() > 5)
        fprintf(stderr, "fc-master: warning: ... and %zu more frame(s) that are not complete "
                        "and correct\n", damaged.size() - 5);
    if (adopted > 0 && !opt_.quiet)
        fprintf(stderr, "fc-master: keeping %d frame(s) already in %s (complete, but made without "
                        "fc-master's record of the run; --force renders them again)\n",
                adopted, outdir_.c_str());
    return true;
}

// Before anything renders: room for the frames still to write, at their encoded size.
bool Master::check_space(const std::vector<bool> &replace)
{
    int todo = 0, replaced = 0;
    for (size_t i = 0; i < scene_.frames.size(); i++) {
        if (frame_stats_[i].resumed)
            continue;
        todo++;
        replaced += replace[i] ? 1 : 0;
    }
    if (todo == 0)
        return true;
    unsigned long long avail = 0;
    std::string err;
    if (!free_bytes(outdir_, avail, err)) {
        fprintf(stderr, "fc-master: output directory: %s\n", err.c_str());
        return false;
    }
    // A frame that replaces one already there reuses its space; one temporary file at a time.
    double frames_needing_room = double(todo - replaced) + 1;
    // With room for the largest a frame can be, the exact size is not needed: finding it
    // means encoding a frame, which loads OpenImageIO (0.3 s) before the slaves start.
    if (double(avail) >= double(assembly_->frame_bytes_bound()) * frames_needing_room +
                            preview_.max_bytes())
        return true;
    bool exact = false;
    double per = double(assembly_->frame_bytes(exact));
    double need = per * frames_needing_room;
    if (double(avail) >= need + preview_.max_bytes())
        return true;
    if (double(avail) >= need) {
        // The frames come first.
        fprintf(stderr, "fc-master: warning: no room for the preview in %s (it needs up to %s "
                        "more): turned off\n", outdir_.c_str(),
                human_bytes(preview_.max_bytes()).c_str());
        preview_.stop();
        return true;
    }
    std::string what = strf("%d frame(s) of %s%s need %s, %s is free", todo,
                            exact ? "" : "up to ", human_bytes(per).c_str(),
                            human_bytes(need).c_str(), human_bytes(double(avail)).c_str());
    if (exact || double(avail) < per) {
        fprintf(stderr, "fc-master: not enough space in %s: %s\n", outdir_.c_str(), what.c_str());
        return false;
    }
    fprintf(stderr, "fc-master: warning: %s may run out of space: %s (uncompressed; %s frames "
                    "are usually smaller)\n", outdir_.c_str(), what.c_str(),
            format_.name.c_str());
    return true;
}

bool Master::prepare_output()
{
    outdir_ = absolute(opt_.output.empty() ? dir_name(scene_.output_name) : opt_.output);
    std::string err;
    std::string stem = base_name(scene_.stem);
    if (!outdir_obj_.open(outdir_, stem + format_.ext, err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    assembly_.reset(new FrameAssembly(outdir_obj_, format_, stem, scene_.digits, scene_.width,
                                      scene_.height, scene_.frames));
    assembly_->remove_stale_temps();
    sched_.reset(new Schedule(tiles_, int(scene_.frames.size()), opt_.division));
    sched_->set_cheap_moves(!opt_.fc);
    cells_total_ = long(tiles_.size()) * long(scene_.frames.size());
    frame_started_.assign(scene_.frames.size(), 0);
    for (size_t i = 0; i < scene_.frames.size(); i++) {
        FrameStat fs;
        fs.frame = scene_.frames[i];
        fs.file = base_name(assembly_->final_path(int(i)));
        frame_stats_.push_back(fs);
    }
    if (opt_.preview)
        preview_.start(outdir_ + "/preview", scene_.width, scene_.height, format_.pixels,
                       int(scene_.frames.size()), now());

    // Frames of another render (scene, options or renderer changed) must not be mixed in.
    Manifest now = manifest();
    std::vector<std::string> diffs;
    if (outdir_obj_.has_previous())
        diffs = outdir_obj_.differences(now);
    int present = 0;
    for (size_t i = 0; i < scene_.frames.size(); i++)
        present += file_exists(assembly_->final_path(int(i))) ? 1 : 0;
    if (!diffs.empty() && present > 0 && !opt_.force) {
        std::string list;
        for (size_t k = 0; k < diffs.size() && k < 6; k++)
            list += "  " + diffs[k] + "\n";
        if (diffs.size() > 6)
            list += strf("  ... and %zu more\n", diffs.size() - 6);
        fprintf(stderr, "fc-master: the %d frame(s) in %s were rendered with other settings:\n%s"
                        "fc-master: use --force to render every frame again (each replaced as it "
                        "completes), or another output directory\n",
                present, outdir_.c_str(), list.c_str());
        return false;
    }
    bool fresh = opt_.force || !diffs.empty();
    // Frames in a directory without a record (written by POV-Ray itself, or by an older
    // fc-master) are kept when they decode completely; with a record, only recorded ones.
    bool adopt = !outdir_obj_.has_previous() && !fresh;
    if (!outdir_obj_.start_run(now, fresh, err)) {
        fprintf(stderr, "fc-master: output directory %s is not writable: %s\n", outdir_.c_str(),
                err.c_str());
        return false;
    }
    std::vector<bool> replace(scene_.frames.size(), false);
    return resume_frames(fresh, adopt, replace) && check_space(replace);
}

bool Master::start_cluster()
{
    std::string err;
    std::string hostfile = opt_.hostfile.empty() ? "" : absolute(opt_.hostfile);
    if (!cluster_.start(opt_.force_private, hostfile, opt_.pvmd_name,
                        std::max(60.0, opt_.timeout / 2), err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    vm_kind_ = cluster_.embedded() ? "private" : "running";
    // The host file's hosts were added before pvm_config (an error names any that failed).
    // Without local slaves, wait (bounded) for a host to render on.
    if (!opt_.local_slaves && cluster_.hosts().size() < 2)
        cluster_.wait_for_hosts(2, std::max(30.0, opt_.timeout / 2));
    spawn_time_ = now();
    if (!cluster_.spawn_all(opt_.local_slaves, opt_.slaves)) {
        fprintf(stderr, "fc-master: no slave could be started\n");
        return false;
    }
    for (auto &kv : cluster_.slaves())
        host_stat(kv.second.host).slaves++;
    return true;
}

RunSummary Master::run_summary(bool ok, double elapsed) const
{
    RunSummary r;
    r.ok = ok;
    r.error = error_;
    r.elapsed = elapsed;
    r.rendered = rendered_;
    r.resumed = resumed_;
    r.skipped = skipped_;
    r.total = int(scene_.frames.size());
    r.division = division_name(opt_.division);
    r.virtual_machine = vm_kind_;
    r.hosts = host_stats_;
    for (auto &kv : r.hosts) {
        auto it = host_frames_.find(kv.first);
        kv.second.frames = it == host_frames_.end() ? 0 : int(it->second.size());
    }
    for (const FrameStat &f : frame_stats_) {
        if (f.resumed)
            continue;
        if (f.retried)
            r.retried++;
        if (f.finished_at >= 0) {
            r.frame_seconds.push_back(f.seconds);
            r.frame_numbers.push_back(f.frame);
        }
    }
    r.lost = ok ? 0 : r.total - r.rendered - r.resumed - r.skipped;
    r.savings = savings_;
    if (fresh_pixels_ > 0 && pixels_traced_ > fresh_pixels_) {
        r.savings.known = true;
        r.savings.rays_full = fresh_rays_ / fresh_pixels_ * pixels_traced_;
        r.savings.seconds_full = fresh_seconds_ / fresh_pixels_ * pixels_traced_;
    }
    return r;
}

void Master::finish(bool ok)
{
    std::string sync_err;
    if (!outdir_obj_.sync_records(sync_err))
        fprintf(stderr, "fc-master: warning: %s: a resume renders again the frames whose "
                "records did not reach the disk\n", sync_err.c_str());
    flush_preview(true);
    if (!opt_.stats.empty() && sched_) {
        RunSummary r = run_summary(ok, start_ > 0 ? now() - start_ : 0.0);
        for (auto &kv : job_stats_)
            if (kv.second.status == "running")
                kv.second.status = "stopped";
        for (auto &kv : host_stats_)
            kv.second.frames = int(host_frames_[kv.first].size());
        std::string head;
        head += "  \"scene\": " + Report::json_string(opt_.pov.empty() ? "" : opt_.pov[0]) + ",\n";
        head += "  \"renderer\": " + Report::json_string(renderer_) + ",\n";
        head += "  \"output\": " + Report::json_string(outdir_) + ",\n";
        head += strf("  \"division\": \"%s\",\n", division_name(opt_.division));
        head += strf("  \"tile\": %d,\n  \"tiles\": %d,\n  \"width\": %d,\n  \"height\": %d,\n",
                     opt_.tile, int(tiles_.size()), scene_.width, scene_.height);
        std::string rects;
        for (size_t k = 0; k < tiles_.size(); k++)
            rects += strf("%s[%d, %d, %d, %d]", k ? ", " : "", tiles_[k].x0, tiles_[k].y0,
                          tiles_[k].x1, tiles_[k].y1);
        head += "  \"tile_rects\": [" + rects + "],\n";
        head += strf("  \"max_frames_held\": %d,\n", max_frames_held_);
        head += strf("  \"frame_coherence\": %s,\n", opt_.fc ? "true" : "false");
        head += strf("  \"virtual_machine\": \"%s\",\n  \"hosts_used\": %d,\n",
                     vm_kind_.c_str(), int(host_stats_.size()));
        head += strf("  \"format\": %s,\n  \"bits_per_color\": %d,\n",
                     Report::json_string(format_.name).c_str(), format_.bits);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        double cpu = double(ru.ru_utime.tv_sec) + ru.ru_utime.tv_usec / 1e6 +
                     double(ru.ru_stime.tv_sec) + ru.ru_stime.tv_usec / 1e6;
        head += strf("  \"master_cpu\": %.3f,\n  \"master_max_rss_kb\": %ld,\n", cpu,
                     long(ru.ru_maxrss));
        head += strf("  \"messages\": %ld,\n", messages_);
        head += strf("  \"success\": %s,\n", ok ? "true" : "false");
        head += strf("  \"elapsed\": %.3f,\n", start_ > 0 ? now() - start_ : 0.0);
        head += strf("  \"frames_total\": %d,\n  \"frames_rendered\": %d,\n  \"frames_resumed\": %d,\n",
                     int(scene_.frames.size()), rendered_, resumed_);
        head += strf("  \"frames_retried\": %d,\n  \"frames_lost\": %d,\n  \"frames_skipped\": %d,\n",
                     r.retried, r.lost, r.skipped);
        head += "  \"error\": " + (ok ? std::string("null") : Report::json_string(error_)) + ",\n";
        if (r.savings.known)
            head += strf("  \"fc_saved\": {\"rays_spent\": %.0f, \"rays_without_fc\": %.0f, "
                         "\"trace_seconds_spent\": %.3f, \"trace_seconds_first_frame_rate\": %.3f},\n",
                         r.savings.rays_spent, r.savings.rays_full, r.savings.seconds_spent,
                         r.savings.seconds_full);
        else
            head += "  \"fc_saved\": null,\n";
        std::string err;
        if (!report_.write_json(opt_.stats, head, frame_stats_, job_stats_, host_stats_, err))
            fprintf(stderr, "fc-master: cannot write statistics: %s\n", err.c_str());
    }
}

int Master::run()
{
    debug_log("master starts");
    // A warning of the image code (fc-image-writer failed) goes through the report, which
    // clears the progress line first: it must not be written onto the end of that line.
    set_image_io_warning_handler([this](const std::string &message) {
        report_.clear_line();
        fprintf(stderr, "fc-master: warning: %s\n", message.c_str());
    });
    if (!resolve_programs() || !probe() || !prepare_output()) {
        if (!tmpdir_.empty())
            remove_tree(tmpdir_);
        return 1;
    }
    remove_tree(tmpdir_);
    tmpdir_.clear();
    if (sched_->finished()) {
        fprintf(stderr, "fc-master: all %zu frame(s) already exist in %s: nothing to render\n",
                scene_.frames.size(), outdir_.c_str());
        finish(true);
        return 0;
    }
    ShelloutResult pre = shellouts_.run(Shellouts::PreScene, scene_.frames.front(),
                                        assembly_->final_path(0));
    if (pre.action != ShelloutResult::Continue) {
        fprintf(stderr, "fc-master: %s\n", pre.message.c_str());
        return pre.action == ShelloutResult::Quit ? 0 : 1;
    }
    debug_log("probes done");
    if (!start_cluster()) {
        cluster_.stop();
        return 1;
    }
    debug_log("slaves spawned");
    int rc = loop();
    debug_log("loop done");
    double elapsed = start_ > 0 ? now() - start_ : 0;
    if (rc != 0)
        shutdown_slaves();
    cluster_.stop();
    debug_log("virtual machine stopped");
    if (rc == 0 && !failed_ && !skip_post_scene_) {
        ShelloutResult post = shellouts_.run(Shellouts::PostScene, scene_.frames.back(),
                                             assembly_->final_path(int(scene_.frames.size()) - 1));
        if (post.action == ShelloutResult::Fatal) {
            fprintf(stderr, "fc-master: %s\n", post.message.c_str());
            rc = 1;
        }
    }
    finish(rc == 0);
    if (!opt_.quiet)
        fputs(report_.summary(run_summary(rc == 0, elapsed)).c_str(), stderr);
    return rc;
}

} // namespace fc
