// slave.cpp - fc-slave: renders jobs for fc-master with one long-lived POV-Ray process.
//
// Spawned by the master through PVM (never run by hand). It says FC_HELLO, receives FC_SETUP,
// then jobs (FC_JOB: one frame, a set of tiles), at most two at a time. Each job goes to the
// renderer (renderer.h) as one frame-control line; the frame comes back on the renderer's
// frame channel and goes to the master as FC_FRAME. The renderer is started again only when
// a job cannot follow the last one (an earlier frame) or after it failed. The renderer dies with the slave
// (PR_SET_PDEATHSIG), the slave with the master (pvm_notify on the master's exit).
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>

#include <pvm3.h>

#include "clock.h"
#include "debug_log.h"
#include "freed_memory.h"
#include "host_info.h"
#include "protocol.h"
#include "pvm_error.h"
#include "renderer.h"
#include "signals.h"
#include "temp_dirs.h"
#include "text.h"

using namespace fc;

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int) { g_stop = 1; }

const double kHeartbeat = 2.0;      // seconds between FC_PROGRESS messages while busy

class Slave {
public:
    bool init(std::string &err);
    int run();
    void cleanup();

    // Tell the master why this slave cannot work (init failed after it learned the master),
    // so the reason ("No space left on device") reaches the user, not only the pvmd's log.
    void report_failure(const std::string &why);

private:
    // Message handlers: one per tag the slave receives.
    void on_setup();
    void on_job();
    void on_cancel();
    void on_abandon();

    // The renderer.
    void feed_renderer();
    void renderer_output();
    bool send_frame(const FrameRecord &rec);
    void fail(const JobMsg &job, const RendererFailure &f, bool abandoned = false);
    void heartbeat();

    int master_ = 0;
    std::string workdir_;
    Setup setup_;
    bool have_setup_ = false;
    double last_master_ = 0;

    Renderer renderer_;
    int renderer_threads_ = 0;
    std::deque<JobMsg> queue_;      // received, not yet given to the renderer
    bool busy_ = false;             // current_ is with the renderer
    JobMsg current_;
    double last_beat_ = 0;
};

bool Slave::init(std::string &err)
{
    pvm_setopt(PvmAutoErr, 0);
    int me = pvm_mytid();
    if (me < 0) {
        err = "pvm_mytid: " + pvm_error(me);
        return false;
    }
    // Frames go to the master over a direct TCP link in 256 KB fragments: through the pvmds
    // they went in 4 KB fragments (a read, a header read and a select each on the master,
    // 5,400 reads for Newton's 45 frames at 320x240; 380 now), and between hosts as pvmd
    // UDP packets. PVM falls back to the pvmds when the link cannot be made. Set after
    // pvm_mytid: joining the virtual machine sets the fragment size the pvmd asks for.
    pvm_setopt(PvmRoute, PvmRouteDirect);
    pvm_setopt(PvmFragSize, 1 << 18);
    master_ = pvm_parent();
    if (master_ < 0) {
        err = "fc-slave is started by fc-master through PVM, not by hand (pvm_parent: " +
              pvm_error(master_) + ")";
        return false;
    }
    int r = pvm_notify(PvmTaskExit, FC_MASTEREXIT, 1, &master_);
    if (r < 0) {
        err = "pvm_notify(PvmTaskExit, master): " + pvm_error(r);
        return false;
    }
    remove_stale_dirs(temp_root(), "fc-slave-");
    if (!make_temp_dir(temp_root(), strf("fc-slave-%d-", int(getpid())), workdir_, err))
        return false;
    Hello h;
    h.host = host_name();
    h.cpus = cpu_count();
    h.pid = int(getpid());
    r = send_msg(master_, FC_HELLO, h);
    if (r < 0) {
        err = "send FC_HELLO: " + pvm_error(r);
        return false;
    }
    last_master_ = now();
    return true;
}

void Slave::cleanup()
{
    renderer_.kill();
    if (!workdir_.empty())
        remove_tree(workdir_);
}

void Slave::on_setup()
{
    Setup s;
    if (!unpack(s)) {
        RendererFailure f;
        f.message = "malformed FC_SETUP message";
        fail(JobMsg(), f);
        return;
    }
    setup_ = s;
    have_setup_ = true;
}

void Slave::on_job()
{
    JobMsg j;
    if (!unpack(j) || !have_setup_) {
        RendererFailure f;
        f.message = have_setup_ ? "malformed FC_JOB message" : "FC_JOB before FC_SETUP";
        fail(j, f);
        return;
    }
    debug_log("job %d: frame %d, %zu tile(s)", j.job, j.frame, j.tiles.size());
    queue_.push_back(j);
    feed_renderer();
}

void Slave::on_cancel()
{
    int job = 0;
    if (!unpack_int(job))
        return;
    for (auto it = queue_.begin(); it != queue_.end(); ++it)
        if (it->job == job) {
            queue_.erase(it);
            debug_log("job %d cancelled before it began", job);
            return;
        }
    if (busy_ && current_.job == job) {
        // Its frame is half rendered: only a new process can drop it. The master hears of it
        // (frame -1): a slave whose job stalled gets work again once it speaks.
        debug_log("job %d cancelled while rendering", job);
        renderer_.kill();
        busy_ = false;
        Progress idle;
        idle.job = job;
        idle.frame = -1;
        if (send_msg(master_, FC_PROGRESS, idle) < 0)
            g_stop = 1;
        feed_renderer();
    }
}

// The master gave up waiting for a job (it never finished within its deadline): the renderer
// is stopped, and POV-Ray's last words go back with the job's failure.
void Slave::on_abandon()
{
    int job = 0;
    if (!unpack_int(job))
        return;
    JobMsg abandoned;
    RendererFailure f;
    f.status = -1;
    if (busy_ && current_.job == job) {
        f.message = renderer_.last_words();
        renderer_.kill();
        busy_ = false;
        abandoned = current_;
    } else {
        auto it = queue_.begin();
        while (it != queue_.end() && it->job != job)
            ++it;
        if (it == queue_.end())
            return;     // already over: its result or failure is on its way
        abandoned = *it;
        queue_.erase(it);
        f.message = "(it had not begun)\n";
    }
    debug_log("job %d abandoned", job);
    fail(abandoned, f, true);
    feed_renderer();
}

// Give the renderer its next job, starting a process when the running one cannot take it.
void Slave::feed_renderer()
{
    while (!busy_ && !queue_.empty() && !g_stop) {
        JobMsg &j = queue_.front();
        if (renderer_.state() == Renderer::Busy)
            return;
        if (!renderer_.can_take(j.frame) || renderer_threads_ != j.threads) {
            RendererConfig c;
            c.program = setup_.renderer;
            c.cwd = setup_.cwd;
            c.options = setup_.options;
            c.extra = setup_.extra;
            c.workdir = workdir_;
            c.threads = j.threads;
            c.nice = setup_.nice;
            c.animated = setup_.digits > 0;
            c.last_frame = setup_.last_frame;
            c.coherent = setup_.coherent != 0;
            std::string err;
            renderer_.stop();
            if (!renderer_.start(c, j.frame, err)) {
                RendererFailure f;
                f.message = "cannot start the renderer: " + err;
                JobMsg failed = j;
                queue_.pop_front();
                fail(failed, f);
                continue;
            }
            renderer_threads_ = j.threads;
        }
        current_ = j;
        queue_.pop_front();
        RendererFailure f;
        if (!renderer_.submit(current_.frame, current_.rects, f)) {
            // The process died before it read the job (pump() had not seen it end yet).
            renderer_.kill();
            fail(current_, f);
            continue;
        }
        busy_ = true;
        last_beat_ = now();
    }
}

bool Slave::send_frame(const FrameRecord &rec)
{
    FrameResult fr;
    static_cast<FrameRecord &>(fr) = rec;
    fr.job = current_.job;
    fr.tiles = current_.tiles;
    fr.fresh = renderer_.fresh_frame() ? 1 : 0;
    int r = send_msg(master_, FC_FRAME, fr);
    if (r < 0) {
        g_stop = 1;     // the master is unreachable
        return false;
    }
    debug_log("sent frame %d of job %d", fr.frame, current_.job);
    return true;
}

void Slave::renderer_output()
{
    std::vector<FrameRecord> done;
    RendererFailure failure;
    bool ok = renderer_.pump(done, failure);
    for (const FrameRecord &rec : done) {
        if (!busy_)
            continue;
        busy_ = false;
        if (!send_frame(rec))
            return;
    }
    if (!ok) {
        if (busy_) {
            busy_ = false;
            fail(current_, failure);
        } else {
            debug_log("idle renderer ended: %s", failure.message.c_str());
        }
    }
    feed_renderer();
}

void Slave::fail(const JobMsg &job, const RendererFailure &f, bool abandoned)
{
    Failure m;
    m.job = job.job;
    m.frame = job.frame;
    m.scene_error = f.scene_error ? 1 : 0;
    m.status = f.status;
    m.abandoned = abandoned ? 1 : 0;
    m.message = f.message;
    debug_log("job %d failed (%s): %s", job.job, f.scene_error ? "scene" : "slave",
              f.message.c_str());
    if (send_msg(master_, FC_FAIL, m) < 0)
        g_stop = 1;
}

void Slave::report_failure(const std::string &why)
{
    if (master_ <= 0)
        return;
    JobMsg none;
    none.job = -1;
    none.frame = -1;
    RendererFailure f;
    f.status = -1;
    f.message = "fc-slave cannot start: " + why;
    fail(none, f);
}

void Slave::heartbeat()
{
    double t = now();
    double every = setup_.timeout > 0 ? std::min(kHeartbeat, setup_.timeout / 4.0) : kHeartbeat;
    if (!busy_ || t - last_beat_ < every)
        return;
    last_beat_ = t;
    Progress p;
    p.job = current_.job;
    p.frame = current_.frame;
    if (send_msg(master_, FC_PROGRESS, p) < 0)
        g_stop = 1;
}

int Slave::run()
{
    while (!g_stop) {
        // Wait for renderer output or a message from the pvmd.
        std::vector<struct pollfd> fds;
        int *pvmfds = nullptr;
        int npvm = pvm_getfds(&pvmfds);
        for (int i = 0; i < npvm; i++)
            fds.push_back({pvmfds[i], POLLIN, 0});
        std::vector<int> rfds;
        renderer_.poll_fds(rfds);
        for (int fd : rfds)
            fds.push_back({fd, POLLIN, 0});
        poll(fds.data(), nfds_t(fds.size()), 200);

        if (renderer_.state() != Renderer::Stopped)
            renderer_output();

        for (;;) {
            int buf = pvm_nrecv(-1, -1);
            if (buf < 0)
                return 3;   // the pvmd is gone
            if (buf == 0)
                break;
            int len, tag, src;
            pvm_bufinfo(buf, &len, &tag, &src);
            debug_log("recv %s from t%x", tag_name(tag), unsigned(src));
            if (src == master_ || tag == FC_MASTEREXIT)
                last_master_ = now();
            switch (tag) {
            case FC_SETUP: on_setup(); break;
            case FC_JOB: on_job(); break;
            case FC_CANCEL: on_cancel(); break;
            case FC_ABANDON: on_abandon(); break;
            case FC_PING: break;
            case FC_QUIT: return 0;
            case FC_MASTEREXIT: return 0;
            default: break;
            }
            pvm_freebuf(buf);
        }
        heartbeat();
        // The master pings idle slaves every timeout/3 s; it can still be held up for
        // minutes inside PVM calls when a host crashes, so give up only much later.
        double idle_limit = std::max(300.0, 10.0 * setup_.timeout);
        if (!busy_ && setup_.timeout > 0 && now() - last_master_ > idle_limit)
            return 4;   // nothing heard from the master for too long
        if (!busy_ && !have_setup_ && now() - last_master_ > 120)
            return 4;
    }
    return 1;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        printf("usage: fc-slave (spawned by fc-master through PVM; see coordinator/README.md)\n");
        return 0;
    }
    install_signal_handlers(on_signal);
    keep_freed_memory();

    Slave slave;
    std::string err;
    if (!slave.init(err)) {
        fprintf(stderr, "fc-slave: %s\n", err.c_str());
        slave.report_failure(err);
        slave.cleanup();
        pvm_exit();
        return 2;
    }
    int rc = slave.run();
    slave.cleanup();
    pvm_exit();
    return rc;
}
