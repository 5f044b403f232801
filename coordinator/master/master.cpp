// master.cpp - fc-master's receive loop and the handlers of the messages; master_setup.cpp does
// what comes before and after.
//
// One receive point: receive any message, switch on its tag, each case a short handler. A
// slave holds at most two jobs and gets the next one in the step that handles a result
// (self-scheduling, schedule.h); results go into the frame book, which writes each frame once
// it is complete (frame_book.h). Timeouts, pings and progress run on a clock, whatever the
// traffic.
#include "master.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include <pvm3.h>

#include "child_process.h"
#include "clock.h"
#include "debug_log.h"
#include "files.h"
#include "protocol.h"
#include "pvm_error.h"
#include "text.h"
#include "watchdog.h"

namespace fc {

namespace {

const double kTick = 0.25;          // seconds between timer checks (timeouts, pings, progress)
const int kJobsAhead = 2;           // jobs a slave holds: the one rendering and the next

// The first line of a multi-line message (for warnings that go on).
std::string first_line(const std::string &s)
{
    size_t nl = s.find('\n');
    return nl == std::string::npos ? s : s.substr(0, nl);
}

} // namespace

void Master::warn(const std::string &message)
{
    report_.clear_line();
    fprintf(stderr, "fc-master: warning: %s\n", message.c_str());
}

// What a shell-out has to say besides its result (POV-Ray's line on a prohibited command).
void Master::tell(const ShelloutResult &r)
{
    if (r.notice.empty())
        return;
    report_.clear_line();
    fprintf(stderr, "fc-master: %s\n", r.notice.c_str());
}

// Cut the frames into ranges once the slaves we started said hello (or 5 s passed): sequence
// division gives each its own range.
void Master::plan_if_ready()
{
    if (planned_)
        return;
    int ready = 0, starting = 0;
    for (auto &kv : cluster_.slaves()) {
        if (kv.second.state == SlaveState::Starting) starting++;
        else if (kv.second.state == SlaveState::Ready) ready++;
    }
    if (ready == 0 || (starting > 0 && now() - spawn_time_ < 5))
        return;
    int parts = opt_.ranges;
    if (parts <= 0)
        parts = opt_.division == Division::Hybrid ? std::max(1, (ready + 1) / 2) : ready;
    sched_->plan(parts, ready + starting);
    planned_ = true;
}

// The first job of a frame runs its Pre_Frame_Command, as one POV-Ray process would. False when
// the job is not to be sent (the frame is skipped, or the render stops).
bool Master::run_pre_frame(const Job &job)
{
    if (!book_->start(job.index))
        return true;
    int frame = book_->number(job.index);
    ShelloutResult r = plan_.shellouts.run(Shellouts::PreFrame, frame,
                                           files_->final_path(job.index));
    tell(r);
    switch (r.action) {
    case ShelloutResult::Continue:
        return true;
    case ShelloutResult::Fatal:
        fatal(r.message);
        return false;
    case ShelloutResult::Quit:
    case ShelloutResult::SkipAll:
        report_.clear_line();
        fprintf(stderr, "fc-master: %s\n", r.message.c_str());
        quit_early_ = true;
        skip_post_scene_ = r.action == ShelloutResult::SkipAll;
        return false;
    case ShelloutResult::SkipFrame: {
        // POV-Ray writes no file for a skipped frame.
        report_.clear_line();
        fprintf(stderr, "fc-master: frame %d: %s\n", frame, r.message.c_str());
        book_->skip(job.index);
        std::vector<Job> cancel;
        sched_->job_done(job.id, job.index, cancel, now());
        cancel_jobs(cancel);
        return false;
    }
    }
    return true;
}

void Master::send_job(SlaveInfo &s, const Job &job)
{
    if (!run_pre_frame(job))
        return;
    JobMsg m;
    m.job = job.id;
    m.frame = book_->number(job.index);
    m.tiles = job.tiles;
    for (int t : job.tiles)
        m.rects.push_back(sched_->tile(t));
    m.threads = cluster_.threads_for(s, sched_->suspended_slaves());
    s.last_given = now();
    int r = send_msg(s.tid, FC_JOB, m);
    debug_log("FC_JOB %d frame %d, %zu tile(s) to t%x", job.id, m.frame, job.tiles.size(),
              unsigned(s.tid));
    stats_.job_sent(job, m.frame, s.host, s.tid);
    if (r < 0)
        slave_gone(s, "cannot be sent work: " + pvm_error(r), false);
}

// Top up every ready slave to kJobsAhead jobs: orphans first, then its range, then splits and
// joins, then straggler copies (schedule.h).
void Master::dispatch()
{
    if (failed_ || quit_early_ || watchdog::stop_requested())
        return;
    plan_if_ready();
    if (!planned_)
        return;
    for (auto &kv : cluster_.slaves()) {
        SlaveInfo &s = kv.second;
        while (s.state == SlaveState::Ready && !failed_ && !quit_early_ &&
               sched_->live_jobs(s.tid) < kJobsAhead) {
            const Job *j = sched_->next_job(s.tid, now(), opt_.duplicates);
            if (!j)
                break;
            send_job(s, *j);
        }
    }
    // Nothing running, yet frames are missing: a bookkeeping bug; do not hang on it.
    bool any_live = !sched_->jobs().empty();
    if (!any_live && !book_->all_rendered() && cluster_.live_slaves() > 0 &&
        sched_->orphans() == 0) {
        bool ranges_idle = true;
        for (auto &kv : cluster_.slaves())
            ranges_idle = ranges_idle && kv.second.state != SlaveState::Starting;
        if (ranges_idle) {
            int n = sched_->repair();
            if (n > 0) {
                warn(strf("%d tile(s) were lost track of and are queued again", n));
                dispatch();
            }
        }
    }
}

void Master::cancel_jobs(const std::vector<Job> &jobs)
{
    for (const Job &j : jobs) {
        debug_log("FC_CANCEL job %d to t%x", j.id, unsigned(j.slave));
        if (pack_int(j.id) >= 0)
            send_packed(j.slave, FC_CANCEL);
        stats_.job_ended(j.id, "cancelled");
    }
}

void Master::on_hello(int src)
{
    Hello h;
    SlaveInfo *s = cluster_.slave(src);
    if (!unpack(h) || !s || s->state != SlaveState::Starting)
        return;
    s->state = SlaveState::Ready;
    s->last_msg = now();
    Setup setup;
    setup.renderer = plan_.renderer;
    setup.cwd = plan_.cwd;
    setup.options = opt_.pov;
    setup.extra = plan_.format_options;
    setup.extra.insert(setup.extra.end(), plan_.extra.begin(), plan_.extra.end());
    setup.width = plan_.scene.width;
    setup.height = plan_.scene.height;
    setup.digits = plan_.scene.digits;
    setup.last_frame = plan_.scene.frames.back();
    setup.coherent = opt_.fc ? 1 : 0;
    setup.timeout = int(std::ceil(opt_.timeout));
    setup.nice = opt_.nice;
    int r = send_msg(src, FC_SETUP, setup);
    if (r < 0) {
        slave_gone(*s, "cannot be sent the setup: " + pvm_error(r), false);
        return;
    }
    HostInfo *host = cluster_.host(s->dtid);
    sched_->add_slave(src, s->dtid);
    int more = cluster_.hello(*s, h.cpus, opt_.slaves);
    if (more > 0 && host)
        stats_.slaves_started(host->name, more);
    dispatch();
}

void Master::on_frame(int src)
{
    FrameResult fr;
    SlaveInfo *s = cluster_.slave(src);
    if (!unpack(fr)) {
        warn(strf("malformed FC_FRAME from t%x", unsigned(src)));
        return;
    }
    if (s)
        s->last_msg = now();
    int idx = book_->index_of(fr.frame);
    bool valid = idx >= 0;
    for (size_t k = 0; valid && k < fr.tiles.size(); k++)
        valid = fr.tiles[k] >= 0 && fr.tiles[k] < sched_->tiles() &&
                sched_->tile(fr.tiles[k]) == fr.rects[k];
    if (!valid) {
        warn(strf("unexpected frame %d of job %d from t%x", fr.frame, fr.job, unsigned(src)));
        return;
    }
    std::string host = s ? s->host : "?";
    // A result without POV-Ray's file of the frame is assembled here: its encoder may need
    // OpenImageIO, which then loads in the background meanwhile.
    if (fr.file.empty())
        encoder_->result_without_file();
    std::vector<int> fresh;
    std::string err;
    if (!book_->deliver(idx, fr, fresh, err)) {
        fatal(strf("frame %d from host %s: %s", fr.frame, host.c_str(), err.c_str()));
        return;
    }
    if (!fresh.empty() && !book_->has_inputs(idx))
        note_inputs(idx, fr, host);
    stats_.frames_held(book_->held());
    stats_.result(fr, idx, fresh, host);
    ResultCost cost;
    cost.slave = src;
    cost.index = idx;
    for (const Rect &r : fr.rects)
        cost.pixels += double(r.area());
    cost.parse = fr.parse_seconds;
    cost.trace = fr.trace_seconds;
    cost.rays = fr.rays;
    cost.fresh = fr.fresh != 0;
    costs_.note_result(cost);
    // How long the job took, what its host's deadlines learn from: the renderer's own parse
    // and trace time (the frame time the goals speak of; a renderer's start-up, once a run, is
    // the fresh cost's), else the time since its slave began it.
    const Job *job = sched_->find(fr.job);
    if (job && job->rendering >= 0 && s) {
        double took = fr.parse_seconds + fr.trace_seconds;
        liveness_.job_took(src, s->dtid, cost.pixels, took > 0 ? took : now() - job->rendering);
    }
    std::vector<Job> cancel;
    sched_->job_done(fr.job, idx, cancel, now());
    cancel_jobs(cancel);
    sched_->resume(src);
    // The slave's next job goes out now; the receive loop writes the frame after this
    // (write_complete_frames), since writing may wait.
    dispatch();
}

// What frame index read, from its first result, hashed now: recorded with the frame, so that
// a resume keeps it only while they are as they were. A renderer that reports nothing read the
// scene file as far as anyone knows.
void Master::note_inputs(int index, const FrameResult &fr, const std::string &host)
{
    FrameInputs inputs;
    std::string err;
    if (fr.reads.empty()) {
        FrameInputs::File scene;
        scene.path = plan_.scene_path;
        inputs.files.push_back(scene);
    } else if (!parse_reads(fr.reads, plan_.cwd, inputs, err)) {
        warn(strf("frame %d from host %s: %s", fr.frame, host.c_str(), err.c_str()));
        inputs.known = false;
    }
    hashes_.fill(inputs, book_->started_at(index));
    book_->set_inputs(index, inputs);
}

// Write the complete frames the book lets go now (wait: all of them). After a failed write or
// a shell-out that asked to stop, nothing more is written, as one POV-Ray process would.
void Master::write_complete_frames(bool wait)
{
    while (!write_failed_ && !quit_early_ && !failed_) {
        int index = book_->next_to_write(wait);
        if (index < 0)
            return;
        std::string err;
        std::vector<uint8_t> samples;
        bool disk_full = false;
        if (!book_->write(index, samples, disk_full, err)) {
            std::string msg = strf("cannot write frame %d: %s", book_->number(index), err.c_str());
            if (disk_full) {
                preview_.stop();    // its files would only take what a frame needs
                unsigned long long avail = 0;
                std::string ignored;
                free_bytes(outdir_.path(), avail, ignored);
                int complete = book_->resumed_count() + book_->written_count();
                int missing = book_->count() - complete - book_->skipped_count();
                msg += strf("\nfc-master: the disk holding %s is full (%s free). The %d frame(s) "
                            "there are complete; free some space and run the same command again "
                            "to render the other %d",
                            outdir_.path().c_str(), human_bytes(double(avail)).c_str(), complete,
                            missing);
            }
            write_failed_ = true;
            fatal(msg);
            return;
        }
        if (!frame_written(index, samples))
            return;
    }
}

// A frame is on disk: the preview shows it and its Post_Frame_Command runs.
bool Master::frame_written(int index, std::vector<uint8_t> &samples)
{
    preview_.add(index, samples);
    stats_.frame_written(index, now() - start_);
    ShelloutResult r = plan_.shellouts.run(Shellouts::PostFrame, book_->number(index),
                                           files_->final_path(index));
    tell(r);
    if (r.action == ShelloutResult::Fatal) {
        fatal(r.message);
        return false;
    }
    if (r.action == ShelloutResult::Quit) {
        report_.clear_line();
        fprintf(stderr, "fc-master: %s\n", r.message.c_str());
        quit_early_ = true;
    }
    return true;
}

void Master::on_progress(int src)
{
    Progress p;
    SlaveInfo *s = cluster_.slave(src);
    if (!unpack(p) || !s)
        return;
    s->last_msg = now();
    s->frame = p.frame;
    // Frame -1: it dropped a cancelled job and waits for work (a stalled slave's word).
    if (sched_->resume(src))
        dispatch();
}

void Master::on_fail(int src)
{
    Failure f;
    SlaveInfo *s = cluster_.slave(src);
    if (!unpack(f))
        return;
    if (s)
        s->last_msg = now();
    std::string host = s ? s->host : "?";
    if (f.abandoned) {
        on_abandoned(f, host);
        if (sched_->resume(src))
            dispatch();
        return;
    }
    std::string what = f.status == -1 ? "slave error" : describe_status(f.status);
    last_failure_ = "on " + host + ": " + first_line(f.message);
    if (f.job < 0) {
        // The slave could not start (no room for its directory, say); its exit follows and
        // it is replaced, up to a host's failure limit.
        warn(strf("slave t%x on host %s: %s", unsigned(src), host.c_str(),
                  first_line(f.message).c_str()));
        stats_.host_failed(host);
        if (s && cluster_.host_failed(*s))
            leave_out_host(s->dtid, first_line(f.message));
        return;
    }
    stats_.job_ended(f.job, "failed");
    int fi = book_->index_of(f.frame);
    if (f.scene_error) {
        std::string why = strf("rendering failed on host %s (frame %d, %s):\n%s", host.c_str(),
                               f.frame, what.c_str(), f.message.c_str());
        if (opt_.keep_going && fi >= 0) {
            sched_->job_failed(f.job, now());
            give_up_frame(fi, why);
        } else {
            fatal(why);
        }
        return;
    }
    // Not the scene's fault: try the job elsewhere, leave out a host that keeps failing. A
    // frame that failed on two hosts (or kRetries times on one) is given up.
    if (fi >= 0)
        stats_.frame_retried(fi);
    int failures = sched_->job_failed(f.job, now());
    sched_->resume(src);
    stats_.host_failed(host);
    if (fi >= 0) {
        FrameBook::Trouble &trouble = book_->trouble(fi);
        trouble.failures++;
        trouble.hosts.insert(host);
        trouble.last_words = f.message;
        if (trouble.hosts.size() >= 2 || failures >= Schedule::kRetries) {
            std::string hosts;
            for (const std::string &h : trouble.hosts)
                hosts += (hosts.empty() ? "" : ", ") + h;
            give_up_frame(fi, strf("frame %d failed %d times, on host%s %s, last (%s):\n%s",
                                   f.frame, std::max(failures, trouble.failures),
                                   trouble.hosts.size() > 1 ? "s" : "", hosts.c_str(),
                                   what.c_str(), f.message.c_str()));
            if (failed_)
                return;
        }
    }
    if (fi < 0 || book_->state(fi) != FrameBook::State::GivenUp)
        warn(strf("frame %d failed on host %s (%s): %s; trying again", f.frame, host.c_str(),
                  what.c_str(), first_line(f.message).c_str()));
    if (s && cluster_.host_failed(*s))
        leave_out_host(s->dtid, first_line(f.message));
    dispatch();
}

// A host whose jobs failed Cluster::kHostFailures times gets no more work.
void Master::leave_out_host(int dtid, const std::string &last_error)
{
    HostInfo *h = cluster_.host(dtid);
    if (!h)
        return;
    warn(strf("host %s failed %d times and is left out (last: %s)", h->name.c_str(), h->failures,
              last_error.c_str()));
    stats_.host_left_out(h->name);
    for (auto &kv : cluster_.slaves()) {
        SlaveInfo &s = kv.second;
        if (s.dtid != dtid || s.state == SlaveState::Gone)
            continue;
        if (pack_empty() >= 0)
            send_packed(s.tid, FC_QUIT);
        slave_gone(s, "is stopped with its host", false);
    }
}

// A slave is gone (exited, killed, its host died): put its work back.
void Master::slave_gone(SlaveInfo &s, const std::string &why, bool respawn)
{
    if (s.state == SlaveState::Gone)
        return;
    s.state = SlaveState::Gone;
    for (auto &kv : sched_->jobs())
        if (kv.second.live && kv.second.slave == s.tid &&
            !book_->cells().frame_done(kv.second.index))
            stats_.frame_retried(kv.second.index);
    std::vector<int> lost = sched_->remove_slave(s.tid);
    for (int id : lost)
        stats_.job_ended(id, "lost");
    if (failed_ || quit_early_ || watchdog::stop_requested() || book_->all_rendered())
        return;
    report_.clear_line();
    fprintf(stderr, "fc-master: slave t%x on %s %s%s\n", unsigned(s.tid), s.host.c_str(),
            why.c_str(), lost.empty() ? "" : "; its unfinished frames are queued again");
    // Replace a slave that exited while its host lives (a few times per host). Not one that
    // fell silent: its host may be unreachable, and pvm_spawn there blocks until PVM gives
    // up on the host (minutes).
    HostInfo *h = cluster_.host(s.dtid);
    if (respawn && h && h->alive && !h->excluded && h->respawns < Cluster::kRespawns) {
        h->respawns++;
        if (cluster_.spawn_on(*h, 1))
            stats_.slaves_started(h->name, 1);
    }
    dispatch();
}

void Master::on_task_exit()
{
    int tid = 0;
    if (!unpack_int(tid))
        return;
    if (SlaveInfo *s = cluster_.slave(tid))
        slave_gone(*s, "exited", true);
}

void Master::on_host_delete()
{
    int dtid = 0;
    if (!unpack_int(dtid))
        return;
    HostInfo *h = cluster_.host(dtid);
    if (!h)
        return;
    h->alive = false;
    for (auto &kv : cluster_.slaves())
        if (kv.second.dtid == dtid)
            slave_gone(kv.second, "was lost with its host", false);
}

void Master::on_host_add()
{
    int n = 0;
    if (!unpack_int(n) || n <= 0)
        return;
    std::vector<int> added(size_t(n), 0);
    if (pvm_upkint(added.data(), n, 1) < 0)
        return;
    std::vector<HostInfo *> joined;
    cluster_.hosts_added(added, joined);
    for (HostInfo *h : joined) {
        report_.clear_line();
        fprintf(stderr, "fc-master: host %s joined\n", h->name.c_str());
        if (book_->all_rendered() || failed_)
            continue;
        if (opt_.slaves > 0)
            h->grown = true;
        int count = opt_.slaves > 0 ? opt_.slaves : 1;
        if (cluster_.spawn_on(*h, count))
            stats_.slaves_started(h->name, count);
    }
}

void Master::check_timeouts()
{
    double t = now();
    for (auto &kv : cluster_.slaves()) {
        SlaveInfo &s = kv.second;
        if (s.state == SlaveState::Gone || s.killed)
            continue;
        bool has_work = s.state == SlaveState::Starting || sched_->live_jobs(s.tid) > 0;
        // A message waiting in our queue means it spoke: we were the slow one.
        double silent = s.silent_for(t);
        if (has_work && silent > opt_.timeout && pvm_probe(s.tid, -1) <= 0) {
            // Its work is re-queued right away. On this host SIGKILL also ends a stopped
            // process. A remote one is only abandoned: pvm_sendsig waits for the remote pvmd,
            // which blocks until PVM declares a crashed host dead (minutes); if it lives, it
            // exits when the master does (FC_MASTEREXIT).
            s.killed = true;
            bool local = s.dtid == cluster_.my_host();
            if (local) {
                watchdog::Guard guard("pvm_sendsig", watchdog::kLocalPvmBound);
                pvm_sendsig(s.tid, SIGKILL);
            }
            slave_gone(s, strf("was silent for %.0f s and is %s", silent,
                               local ? "stopped" : "abandoned"), false);
            continue;
        }
        if (!has_work && t - std::max(s.last_ping, s.last_msg) > std::max(1.0, opt_.timeout / 3)) {
            s.last_ping = t;
            if (pack_empty() >= 0)
                send_packed(s.tid, FC_PING);
        }
    }
}

void Master::work_done(double &elapsed, double &fraction, double &eta) const
{
    elapsed = start_ > 0 ? now() - start_ : 0;
    // Only this run's work: the tiles of frames already there are neither done nor to do.
    long tiles = sched_->tiles();
    int resumed = book_->resumed_count();
    long todo = tiles * long(book_->count() - resumed);
    long done = book_->cells().cells_done() - tiles * long(resumed);
    fraction = todo > 0 ? double(std::max(0L, done)) / double(todo) : 1;
    eta = fraction > 0.02 && fraction < 1 ? elapsed * (1 - fraction) / fraction : -1;
}

ProgressState Master::progress_state() const
{
    ProgressState p;
    p.resumed = book_->resumed_count();
    p.frames_todo = book_->count() - p.resumed;
    p.frames_done = book_->written_count() + book_->skipped_count();
    work_done(p.elapsed, p.fraction, p.eta);
    std::set<int> flight;
    for (auto &kv : sched_->jobs())
        if (kv.second.live)
            flight.insert(book_->number(kv.second.index));
    p.in_flight.assign(flight.begin(), flight.end());
    p.frame_pixels = double(plan_.scene.area.area());
    std::map<std::string, HostProgress> live;
    for (auto &kv : const_cast<Cluster &>(cluster_).slaves()) {
        const SlaveInfo &sl = kv.second;
        if (sl.state == SlaveState::Gone)
            continue;
        HostProgress &h = live[sl.host];
        h.name = sl.host;
        h.slaves++;
        p.slaves++;
        if (sched_->live_jobs(kv.first) > 0) {
            h.busy++;
            p.busy++;
        }
    }
    for (auto &kv : live) {
        kv.second.pixels = stats_.host_pixels(kv.first);
        p.hosts.push_back(kv.second);
    }
    return p;
}

void Master::progress()
{
    // The summary says when it is done: progress never shows a finished run.
    if (book_->all_rendered())
        return;
    report_.progress(progress_state());
}

void Master::flush_preview(bool force)
{
    std::string err;
    double elapsed = 0, fraction = 0, eta = -1;
    if (!force)
        work_done(elapsed, fraction, eta);
    if (!preview_.flush(now(), force, err, eta))
        warn("the preview is turned off: " + err);
}

void Master::fatal(const std::string &msg)
{
    if (failed_)
        return;     // report the first error only
    failed_ = true;
    error_ = msg;
    report_.clear_line();
    fprintf(stderr, "fc-master: %s", msg.c_str());
    if (msg.empty() || msg.back() != '\n')
        fputc('\n', stderr);
    shutdown_slaves();
}

// Tell every slave to quit, wait (bounded) for the ones on this host to go, kill stragglers.
// Slaves elsewhere are not waited for: they exit on FC_QUIT, or on FC_MASTEREXIT should the
// quit be lost, and their pvmd reports the exit only once the slave's host has run it (on a
// loaded host, or one held to a CPU quota, tens of milliseconds after its last frame).
void Master::shutdown_slaves()
{
    std::vector<int> live;
    for (auto &kv : cluster_.slaves())
        if (kv.second.state != SlaveState::Gone || !kv.second.killed)
            live.push_back(kv.first);
    for (int tid : live)
        if (pack_empty() >= 0)
            send_packed(tid, FC_QUIT);
    // Under a stop signal the process has a second in all (watchdog.h): no long wait.
    double deadline = now() + (watchdog::stop_requested() ? 0.3 : 5);
    std::set<int> waiting;
    for (int tid : live) {
        SlaveInfo *s = cluster_.slave(tid);
        if (s->state == SlaveState::Gone)
            continue;
        if (s->dtid == cluster_.my_host() && !sched_->suspended(tid))
            waiting.insert(tid);
        else if (s->dtid == cluster_.my_host())
            kill_local_slave(tid);      // it stopped answering: no use waiting for it
        if (!waiting.count(tid))
            s->state = SlaveState::Gone;
    }
    while (!waiting.empty() && now() < deadline) {
        struct timeval tv = {0, 100000};
        int buf = 0;
        {
            watchdog::Guard guard("pvm_trecv", watchdog::kLocalPvmBound);
            buf = pvm_trecv(-1, FC_TASKEXIT, &tv);
        }
        if (buf < 0)
            break;
        if (buf == 0)
            continue;
        int tid = 0;
        if (unpack_int(tid)) {
            waiting.erase(tid);
            if (SlaveInfo *s = cluster_.slave(tid))
                s->state = SlaveState::Gone;
        }
    }
    for (int tid : waiting) {
        kill_local_slave(tid);
        if (SlaveInfo *s = cluster_.slave(tid))
            s->state = SlaveState::Gone;
    }
}

// SIGKILL also ends a stopped process.
void Master::kill_local_slave(int tid)
{
    watchdog::Guard guard("pvm_sendsig", watchdog::kLocalPvmBound);
    pvm_sendsig(tid, SIGKILL);
}

// What the clock does every kTick seconds, whatever the traffic.
void Master::tick()
{
    if (!planned_)
        dispatch();
    check_timeouts();
    check_stalls();
    conclude_hangs(false);
    if (failed_)
        return;
    flush_preview(false);
    if (cluster_.live_slaves() == 0 && !book_->all_rendered() && !failed_) {
        fatal("no slave is left to render the remaining frames" +
              (last_failure_.empty() ? std::string() : " (last failure " + last_failure_ + ")"));
        return;
    }
    progress();
}

int Master::loop()
{
    start_ = now();
    next_tick_ = start_;    // the first tick at once: the progress line shows from the start
    while (!book_->all_rendered() && !failed_ && !quit_early_) {
        if (int sig = watchdog::stop_requested()) {
            report_.clear_line();
            fprintf(stderr, "fc-master: interrupted (%s): stopping the slaves\n", strsignal(sig));
            shutdown_slaves();
            write_complete_frames(true);    // what was rendered is kept
            return 128 + sig;
        }
        double wait = std::max(0.0, next_tick_ - now());
        struct timeval tv = {long(wait), long((wait - std::floor(wait)) * 1e6)};
        int buf = 0;
        {
            watchdog::Guard guard("pvm_trecv", wait + watchdog::kLocalPvmBound);
            buf = pvm_trecv(-1, -1, &tv);
        }
        if (buf < 0) {
            fatal("lost contact with the PVM daemon: " + pvm_error(buf));
            break;
        }
        if (buf > 0) {
            int len = 0, tag = 0, src = 0;
            pvm_bufinfo(buf, &len, &tag, &src);
            stats_.message_received();
            debug_log("recv %s from t%x (%d bytes)", tag_name(tag), unsigned(src), len);
            switch (tag) {
            case FC_HELLO: on_hello(src); break;
            case FC_FRAME: on_frame(src); break;
            case FC_PROGRESS: on_progress(src); break;
            case FC_FAIL: on_fail(src); break;
            case FC_TASKEXIT: on_task_exit(); break;
            case FC_HOSTDEL: on_host_delete(); break;
            case FC_HOSTADD: on_host_add(); break;
            default:
                warn(strf("unexpected message %s (%d) from t%x", tag_name(tag), tag,
                          unsigned(src)));
            }
            pvm_freebuf(buf);
        }
        if (failed_)
            break;
        write_complete_frames(false);
        if (now() < next_tick_)
            continue;
        next_tick_ = now() + kTick;
        tick();
        if (failed_)
            break;
    }
    // Complete frames are kept after a scene error too, as they are by one POV-Ray process.
    write_complete_frames(true);
    if (failed_)
        return exit_code_ != 0 ? exit_code_ : 1;
    report_.clear_line();
    shutdown_slaves();
    // --keep-going rendered what it could; frames given up make the run a failure.
    if (exit_code_ == 0 && book_->given_up_count() > 0)
        exit_code_ = 1;
    return exit_code_;
}

} // namespace fc
