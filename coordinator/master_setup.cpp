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
#include <thread>

#include "master.h"
#include "util.h"

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

bool make_dirs(const std::string &dir, std::string &err)
{
    std::string acc;
    size_t pos = 0;
    while (pos <= dir.size()) {
        size_t slash = dir.find('/', pos);
        if (slash == std::string::npos)
            slash = dir.size();
        acc = dir.substr(0, slash);
        if (!acc.empty() && mkdir(acc.c_str(), 0777) != 0 && errno != EEXIST)
            return sys_fail(err, "mkdir " + acc);
        pos = slash + 1;
    }
    struct stat st;
    if (stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        err = dir + " is not a directory";
        return false;
    }
    return true;
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
        ini_ok = probe_resolved_options(renderer_, opt_.pov, cwd_, tmpdir_, limit, ini, ini_err);
    });
    bool scene_ok = probe_scene(renderer_, opt_.pov, cwd_, tmpdir_, limit, scene_, scene_err);
    resolved.join();
    err = !scene_ok ? scene_err : ini_err;
    if (scene_ok && ini_ok && !set_frames(scene_, ini, err))
        ini_ok = false;
    if (!scene_ok || !ini_ok) {
        fprintf(stderr, "fc-master: %s", err.c_str());
        if (err.empty() || err.back() != '\n')
            fputc('\n', stderr);
        return false;
    }
    // A renderer with the frame channel (the shell-out probe needs it) has frame coherence:
    // the channel's patches come after fc's.
    if (opt_.fc)
        extra_.push_back(kFrameCoherenceOption);
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

bool Master::prepare_output()
{
    outdir_ = opt_.output.empty() ? dir_name(scene_.output_name) : opt_.output;
    std::string err;
    if (!make_dirs(outdir_, err)) {
        fprintf(stderr, "fc-master: output directory: %s\n", err.c_str());
        return false;
    }
    outdir_ = absolute(outdir_);
    std::string stem = base_name(scene_.stem);
    assembly_.reset(new FrameAssembly(outdir_, stem, scene_.digits, scene_.width, scene_.height,
                                      scene_.frames));
    assembly_->remove_stale_temps();
    sched_.reset(new Schedule(tiles_, int(scene_.frames.size()), opt_.division));
    sched_->set_cheap_moves(extra_.empty());
    cells_total_ = long(tiles_.size()) * long(scene_.frames.size());
    frame_started_.assign(scene_.frames.size(), 0);
    for (size_t i = 0; i < scene_.frames.size(); i++) {
        FrameStat fs;
        fs.frame = scene_.frames[i];
        fs.file = base_name(assembly_->final_path(int(i)));
        if (assembly_->exists_complete(int(i))) {
            fs.resumed = true;
            sched_->mark_frame_done(int(i));
            resumed_++;
        }
        frame_stats_.push_back(fs);
    }
    return true;
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
    // A private pvmd adds its host file's hosts in the background: wait (bounded) for them,
    // or the master's own slaves could finish a short render alone.
    size_t want = 1;
    if (!hostfile.empty() && cluster_.embedded())
        want += size_t(Cluster::hostfile_hosts(hostfile));
    if (!opt_.local_slaves)
        want = std::max(want, size_t(2));
    if (want > 1)
        cluster_.wait_for_hosts(want, std::max(30.0, opt_.timeout / 2));
    spawn_time_ = now();
    if (!cluster_.spawn_all(opt_.local_slaves, opt_.slaves)) {
        fprintf(stderr, "fc-master: no slave could be started\n");
        return false;
    }
    for (auto &kv : cluster_.slaves())
        host_stat(kv.second.host).slaves++;
    return true;
}

void Master::finish(bool ok)
{
    if (!opt_.stats.empty() && sched_) {
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
        head += strf("  \"frame_coherence\": %s,\n", extra_.empty() ? "false" : "true");
        head += strf("  \"virtual_machine\": \"%s\",\n  \"hosts_used\": %d,\n",
                     vm_kind_.c_str(), int(cluster_.hosts().size()));
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
        std::string err;
        if (!report_.write_json(opt_.stats, head, frame_stats_, job_stats_, host_stats_, err))
            fprintf(stderr, "fc-master: cannot write statistics: %s\n", err.c_str());
    }
}

int Master::run()
{
    debug_log("master starts");
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
    if (rc == 0 && !opt_.quiet) {
        for (auto &kv : host_stats_)
            kv.second.frames = int(host_frames_[kv.first].size());
        fputs(report_.summary(elapsed, rendered_, resumed_, division_name(opt_.division),
                              host_stats_).c_str(), stderr);
        fprintf(stderr, "  (%zu host(s) of a %s virtual machine)\n", cluster_.hosts().size(),
                vm_kind_ == "private" ? "private" : "running");
    }
    return rc;
}

} // namespace fc
