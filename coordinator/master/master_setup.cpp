// master_setup.cpp - fc-master before and after the receive loop: the plan, the output
// directory and its frames, the virtual machine and the slaves, and the end of the run.
#include "master.h"

#include <cstdio>

#include "clock.h"
#include "debug_log.h"
#include "files.h"
#include "output_setup.h"
#include "text.h"
#include "watchdog.h"

namespace fc {

// Everything before the virtual machine: the plan, then the output directory and its frames.
bool Master::set_up()
{
    std::string err;
    if (!make_render_plan(opt_, plan_, err)) {
        fprintf(stderr, "fc-master: %s", err.c_str());
        if (err.empty() || err.back() != '\n')
            fputc('\n', stderr);
        return false;
    }
    const SceneInfo &scene = plan_.scene;
    encoder_.reset(new FrameEncoder(plan_.format, opt_.division));
    // A warning of the image code (fc-image-writer failed) goes through the report, which
    // clears the progress line first: it must not be written onto the end of that line.
    encoder_->on_warning([this](const std::string &message) { warn(message); });
    encoder_->preload_for_run();

    std::string outdir = absolute_path(opt_.output.empty() ? dir_name(scene.output_name)
                                                           : opt_.output);
    std::string stem = base_name(scene.stem);
    if (!outdir_.open(outdir, stem + plan_.format.ext, err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    files_.reset(new FrameFiles(outdir_, plan_.format, stem, scene.digits, scene.width,
                                scene.height, scene.frames));
    files_->remove_stale_temps();
    book_.reset(new FrameBook(*files_, *encoder_, scene.width, scene.height, scene.frames,
                              int(plan_.tiles.size())));
    costs_.set_frame_coherence(opt_.fc);
    sched_.reset(new Schedule(plan_.tiles, book_->cells(), costs_, opt_.division));
    std::vector<std::string> names;
    for (int i = 0; i < book_->count(); i++)
        names.push_back(files_->file_name(i));
    stats_.set_frames(scene.frames, names);
    if (opt_.preview)
        preview_.start(outdir + "/preview", scene.width, scene.height, plan_.format.pixels,
                       book_->count(), now());
    return prepare_output(opt_, plan_, outdir_, *encoder_, *book_, preview_, stats_, hashes_);
}

bool Master::start_cluster()
{
    std::string err;
    std::string hostfile = opt_.hostfile.empty() ? "" : absolute_path(opt_.hostfile);
    cluster_.slave_prog = plan_.slave_program;
    if (!cluster_.start(opt_.force_private, hostfile, opt_.pvmd_name,
                        std::max(60.0, opt_.timeout / 2), err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
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
        stats_.slaves_started(kv.second.host, 1);
    return true;
}

RunFacts Master::facts(bool ok, double elapsed) const
{
    RunFacts f;
    f.scene = opt_.pov.empty() ? "" : opt_.pov[0];
    f.renderer = plan_.renderer;
    f.output = outdir_.path();
    f.division = opt_.division;
    f.tile = opt_.tile;
    f.width = plan_.scene.width;
    f.height = plan_.scene.height;
    f.tiles = plan_.tiles;
    f.frame_coherence = opt_.fc;
    f.virtual_machine = cluster_.kind();
    f.format = plan_.format.name;
    f.bits_per_color = plan_.format.bits;
    f.ok = ok;
    f.error = error_;
    f.elapsed = elapsed;
    f.total = book_ ? book_->count() : 0;
    f.rendered = book_ ? book_->written_count() : 0;
    f.resumed = book_ ? book_->resumed_count() : 0;
    f.skipped = book_ ? book_->skipped_count() : 0;
    if (book_)
        f.given_up = book_->given_up();
    f.savings = costs_.savings();
    return f;
}

void Master::finish(bool ok)
{
    std::string err;
    if (!outdir_.sync_records(err))
        warn(err + ": a resume renders again the frames whose records did not reach the disk");
    flush_preview(true);
    if (!opt_.stats.empty() && sched_ &&
        !stats_.write_json(opt_.stats, facts(ok, start_ > 0 ? now() - start_ : 0.0), err)) {
        report_.clear_line();
        fprintf(stderr, "fc-master: cannot write statistics: %s\n", err.c_str());
    }
}

int Master::run()
{
    debug_log("master starts");
    if (!set_up())
        return watchdog::stop_requested() ? 128 + watchdog::stop_requested() : 1;
    if (book_->all_rendered()) {
        fprintf(stderr, "fc-master: all %d frame(s) already exist in %s: nothing to render\n",
                book_->count(), outdir_.path().c_str());
        finish(true);
        return 0;
    }
    ShelloutResult pre = plan_.shellouts.run(Shellouts::PreScene, plan_.scene.frames.front(),
                                             files_->final_path(0));
    tell(pre);
    if (pre.action != ShelloutResult::Continue) {
        fprintf(stderr, "fc-master: %s\n", pre.message.c_str());
        return pre.action == ShelloutResult::Quit ? 0 : 1;
    }
    debug_log("probes done");
    if (!start_cluster()) {
        cluster_.stop();
        return watchdog::stop_requested() ? 128 + watchdog::stop_requested() : 1;
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
        int last = book_->count() - 1;
        ShelloutResult post = plan_.shellouts.run(Shellouts::PostScene, book_->number(last),
                                                  files_->final_path(last));
        tell(post);
        if (post.action == ShelloutResult::Fatal) {
            fprintf(stderr, "fc-master: %s\n", post.message.c_str());
            rc = 1;
        }
    }
    finish(rc == 0);
    if (!opt_.quiet)
        fputs(report_.summary(stats_.summary(facts(rc == 0, elapsed))).c_str(), stderr);
    return rc;
}

} // namespace fc
