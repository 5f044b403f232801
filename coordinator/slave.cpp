// slave.cpp - fc-slave: renders work units for fc-master with one POV-Ray process per unit.
//
// Spawned by the master through PVM (never run by hand). It says FC_HELLO, receives FC_SETUP,
// then one FC_JOB at a time: a rectangle of the image over a consecutive frame range. It runs
// POV-Ray once for the whole range (+SF/+EF, +SC/+EC/+SR/+ER) with output into a private
// directory and follows POV-Ray's console output: "Rendering frame k of n" for frame k+1 is
// printed only after frame k's file was written, so at that moment frame k is read, cropped to
// the rectangle and sent back as FC_FRAME. FC_TRUNCATE lowers the last frame (never below the
// frame being rendered); once it is done POV-Ray is killed. The renderer dies with the slave
// (PR_SET_PDEATHSIG), the slave dies with the master (pvm_notify on the master's exit).
#include <poll.h>
#include <sys/stat.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>

#include <OpenImageIO/imageio.h>
#include <pvm3.h>

#include "protocol.h"
#include "povray.h"
#include "pvmutil.h"
#include "util.h"

using namespace fc;

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int) { g_stop = 1; }

const double kHeartbeat = 2.0;      // seconds between FC_PROGRESS messages while busy
const size_t kTailLines = 60;       // renderer output kept for error reports

class Slave {
public:
    bool init(std::string &err);
    int run();
    void cleanup();

private:
    // Message handlers: one per tag the slave receives.
    void on_setup();
    void on_job();
    void on_truncate();
    void on_cancel();

    // Renderer output and lifetime.
    void on_line(const std::string &line);
    void frame_written();
    void advance_to(int k);
    bool send_frame(int k, int frame, double seconds);
    void flush_ready(bool force);
    void check_stopping();
    void renderer_exited(int status);
    void stop_unit(int status);
    void finish_unit(int status);
    void fail(int frame, int status, const std::string &message);
    void heartbeat();

    int master_ = 0;
    std::string workdir_;
    Setup setup_;
    bool have_setup_ = false;
    double last_master_ = 0;

    // The unit being rendered.
    bool busy_ = false;
    Job job_;
    std::string jobdir_;
    Child child_;
    int cur_k_ = 0;             // last "Rendering frame k" seen (1-based), 0 before the first
    int cur_frame_ = 0;         // frame number being rendered
    bool cur_done_ = false;     // cur_frame_ is on disk
    int stop_after_ = 0;        // last frame to deliver (job_.last, lowered by FC_TRUNCATE)
    bool stopping_ = false;     // past stop_after_: deliver what is ready, then kill POV-Ray
    double stop_deadline_ = 0;
    double unit_start_ = 0, frame_start_ = 0, last_beat_ = 0;
    double rays_total_ = 0;
    // POV-Ray prints a frame's statistics asynchronously, sometimes after "Rendering frame"
    // of the next one: finished frames wait here (briefly) for their "Rays:" line, the n-th
    // of which belongs to the n-th frame of the unit.
    struct Ready { int k, frame; double seconds, since; };
    std::deque<Ready> ready_;
    std::vector<double> rays_;
    int frames_sent_ = 0, aa_method_ = 0;
    int px_done_ = 0, px_total_ = 0;
    std::deque<std::string> tail_;
};

bool Slave::init(std::string &err)
{
    pvm_setopt(PvmAutoErr, 0);
    int me = pvm_mytid();
    if (me < 0) {
        err = "pvm_mytid: " + pvm_error(me);
        return false;
    }
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
    remove_stale_dirs("/tmp", "fc-slave-");
    if (!make_temp_dir("/tmp", strf("fc-slave-%d-", int(getpid())), workdir_, err))
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
    kill_child(child_);
    if (!workdir_.empty())
        remove_tree(workdir_);
}

void Slave::on_setup()
{
    Setup s;
    if (!unpack(s)) {
        fail(0, -1, "malformed FC_SETUP message");
        return;
    }
    setup_ = s;
    have_setup_ = true;
}

void Slave::on_job()
{
    Job j;
    if (!unpack(j) || !have_setup_) {
        fail(j.unit, -1, have_setup_ ? "malformed FC_JOB message" : "FC_JOB before FC_SETUP");
        return;
    }
    if (busy_) {
        fail(j.unit, -1, strf("FC_JOB for unit %d while unit %d runs", j.unit, job_.unit));
        return;
    }
    job_ = j;
    jobdir_ = workdir_ + strf("/u%d", j.unit);
    remove_tree(jobdir_);
    if (mkdir(jobdir_.c_str(), 0700) != 0) {
        std::string err;
        sys_fail(err, "mkdir " + jobdir_);
        fail(j.unit, -1, err);
        return;
    }
    // The thread count goes first, so a +WT among the user's options overrides it.
    std::vector<std::string> argv = {setup_.renderer, strf("+WT%d", std::max(1, j.threads))};
    argv.insert(argv.end(), setup_.options.begin(), setup_.options.end());
    argv.insert(argv.end(), setup_.extra.begin(), setup_.extra.end());
    argv.insert(argv.end(), {"-D", "+FT", "-UA", "+O" + jobdir_ + "/f"});
    if (setup_.digits > 0) {
        argv.push_back(strf("+SF%d", j.first));
        argv.push_back(strf("+EF%d", j.last));
    }
    // Only narrow the render area when needed; POV-Ray's +SC/+EC/+SR/+ER are 1-based, inclusive.
    if (!(j.rect == Rect{0, 0, setup_.width, setup_.height})) {
        argv.push_back(strf("+SC%d", j.rect.x0 + 1));
        argv.push_back(strf("+EC%d", j.rect.x1));
        argv.push_back(strf("+SR%d", j.rect.y0 + 1));
        argv.push_back(strf("+ER%d", j.rect.y1));
    }
    std::string err;
    debug_log("unit %d: frames %d..%d rect %d,%d-%d,%d", j.unit, j.first, j.last, j.rect.x0,
              j.rect.y0, j.rect.x1, j.rect.y1);
    if (!start_child(argv, setup_.cwd, setup_.nice, child_, err)) {
        fail(j.unit, -1, err);
        return;
    }
    busy_ = true;
    cur_k_ = 0;
    cur_frame_ = j.first;
    cur_done_ = false;
    stop_after_ = j.last;
    stopping_ = false;
    unit_start_ = frame_start_ = last_beat_ = now();
    rays_total_ = 0;
    ready_.clear();
    rays_.clear();
    frames_sent_ = 0;
    aa_method_ = 0;
    px_done_ = px_total_ = 0;
    tail_.clear();
}

void Slave::on_truncate()
{
    Truncate t;
    if (!unpack(t))
        return;
    Truncate reply;
    reply.unit = t.unit;
    if (!busy_ || job_.unit != t.unit) {
        reply.last = -1;
    } else {
        // Never below the frame being rendered: it is half done and must be delivered.
        int current = cur_frame_;
        int accepted = std::max(t.last, current);
        if (accepted < stop_after_)
            stop_after_ = accepted;
        reply.last = stop_after_;
    }
    debug_log("truncate unit %d to %d: accepted %d", t.unit, t.last, reply.last);
    send_msg(master_, FC_TRUNCATED, reply);
}

void Slave::on_cancel()
{
    int unit = 0;
    if (!unpack_int(unit))
        return;
    if (busy_ && job_.unit == unit)
        stop_unit(UNIT_CANCELLED);
}

void Slave::on_line(const std::string &line)
{
    tail_.push_back(line);
    if (tail_.size() > kTailLines)
        tail_.pop_front();
    int k, n;
    double rays;
    if (parse_rendering_frame(line, k, n)) {
        if (k > cur_k_ && !stopping_)
            advance_to(k);
    } else if (parse_rays(line, rays)) {
        rays_.push_back(rays);
    } else if (parse_aa(line, k)) {
        aa_method_ = k;
    } else if (parse_rendered(line, k, n)) {
        px_done_ = k;
        px_total_ = n;
    }
}

// Frame cur_frame_ is on disk: queue it for delivery.
void Slave::frame_written()
{
    if (cur_done_)
        return;
    cur_done_ = true;
    double t = now();
    ready_.push_back(Ready{cur_k_, cur_frame_, t - frame_start_, t});
}

// POV-Ray announced frame k of the unit (1-based): every frame before it is on disk. Queue
// them all (POV-Ray's console can drop an announcement when frames are short) and make k
// the frame being rendered; past the truncation point, start stopping instead.
void Slave::advance_to(int k)
{
    if (k > cur_k_ + 1 && cur_k_ > 0)
        debug_log("unit %d: announcements %d..%d missed", job_.unit, cur_k_ + 1, k - 1);
    while (cur_k_ < k) {
        if (cur_k_ > 0)
            frame_written();
        cur_k_++;
        cur_frame_ = job_.first + (cur_k_ - 1) * job_.step;
        cur_done_ = false;
        frame_start_ = now();
        px_done_ = 0;
        if (cur_frame_ > stop_after_) {
            stopping_ = true;
            stop_deadline_ = now() + 1.0;
            return;
        }
    }
}

// Send ready frames whose statistics arrived (or waited long enough, or force).
void Slave::flush_ready(bool force)
{
    while (busy_ && !ready_.empty()) {
        const Ready &r = ready_.front();
        if (!force && int(rays_.size()) < r.k && now() - r.since < 2.0)
            break;
        Ready item = r;
        ready_.pop_front();
        if (!send_frame(item.k, item.frame, item.seconds))
            return;
    }
}

// A truncated unit passed its last frame: deliver, then stop POV-Ray (it is parsing the
// next frame, which nobody wants).
void Slave::check_stopping()
{
    if (!busy_ || !stopping_)
        return;
    if (!ready_.empty() && now() < stop_deadline_)
        return;
    flush_ready(true);
    if (busy_)
        stop_unit(UNIT_TRUNCATED);
}

// Read frame number `frame` (the k-th of the unit) from disk, crop it and send it.
bool Slave::send_frame(int k, int frame, double seconds)
{
    std::string path = jobdir_ + "/" + frame_file_name("f", setup_.digits, frame);
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        fail(frame, -1, strf("cannot read the rendered frame %s: %s", path.c_str(),
                             OIIO::geterror().c_str()));
        return false;
    }
    const OIIO::ImageSpec &spec = in->spec();
    if (spec.width != setup_.width || spec.height != setup_.height || spec.nchannels < 3) {
        fail(frame, -1, strf("%s is %dx%d with %d channels, expected %dx%d RGB", path.c_str(),
                             spec.width, spec.height, spec.nchannels, setup_.width,
                             setup_.height));
        return false;
    }
    std::vector<uint8_t> full(size_t(spec.width) * size_t(spec.height) * 3);
    bool ok = in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, full.data());
    std::string read_err = ok ? "" : in->geterror();
    in->close();
    unlink(path.c_str());
    if (!ok) {
        fail(frame, -1, "reading " + path + ": " + read_err);
        return false;
    }
    FrameResult fr;
    fr.unit = job_.unit;
    fr.frame = frame;
    fr.rect = job_.rect;
    fr.rays = int(rays_.size()) >= k ? rays_[size_t(k - 1)] : 0;
    fr.seconds = seconds;
    fr.aa_method = aa_method_;
    size_t row = size_t(fr.rect.width()) * 3;
    fr.pixels.resize(row * size_t(fr.rect.height()));
    for (int y = fr.rect.y0; y < fr.rect.y1; y++)
        memcpy(&fr.pixels[size_t(y - fr.rect.y0) * row],
               &full[(size_t(y) * size_t(setup_.width) + size_t(fr.rect.x0)) * 3], row);
    int r = send_msg(master_, FC_FRAME, fr);
    if (r < 0) {
        g_stop = 1;     // the master is unreachable
        return false;
    }
    frames_sent_++;
    rays_total_ += fr.rays;
    debug_log("sent frame %d of unit %d", frame, job_.unit);
    return true;
}

void Slave::renderer_exited(int status)
{
    if (!busy_)
        return;
    debug_log("renderer of unit %d exited: %s (frame %d, k %d, stop after %d)", job_.unit,
              describe_status(status).c_str(), cur_frame_, cur_k_, stop_after_);
    if (stopping_) {
        flush_ready(true);
        if (busy_)
            finish_unit(UNIT_TRUNCATED);
        return;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        // Every frame up to the last one of the (possibly truncated) range is on disk.
        int last_k = (stop_after_ - job_.first) / job_.step + 1;
        if (cur_k_ > last_k) {
            fail(cur_frame_, status,
                 strf("the renderer announced frame %d of %d\n%s", cur_k_, last_k,
                      error_excerpt({tail_.begin(), tail_.end()}).c_str()));
            return;
        }
        advance_to(last_k);
        frame_written();
        flush_ready(true);
        if (busy_)
            finish_unit(UNIT_FINISHED);
        return;
    }
    flush_ready(true);      // frames finished before the failure are good
    std::vector<std::string> tail(tail_.begin(), tail_.end());
    std::string excerpt = error_excerpt(tail);
    if (excerpt.empty())
        for (const std::string &l : tail)
            excerpt += l + "\n";
    fail(cur_frame_, status, excerpt);
}

void Slave::stop_unit(int status)
{
    kill_child(child_);
    finish_unit(status);
}

void Slave::finish_unit(int status)
{
    kill_child(child_);
    debug_log("unit %d ends, status %d, %d frames", job_.unit, status, frames_sent_);
    UnitDone d;
    d.unit = job_.unit;
    d.status = status;
    d.frames = frames_sent_;
    d.rays = rays_total_;
    d.seconds = now() - unit_start_;
    busy_ = false;
    remove_tree(jobdir_);
    if (send_msg(master_, FC_DONE, d) < 0)
        g_stop = 1;
}

void Slave::fail(int frame, int status, const std::string &message)
{
    kill_child(child_);
    Failure f;
    f.unit = job_.unit;
    f.frame = frame;
    f.status = status;
    f.message = message;
    busy_ = false;
    if (!jobdir_.empty())
        remove_tree(jobdir_);
    if (send_msg(master_, FC_FAIL, f) < 0)
        g_stop = 1;
}

void Slave::heartbeat()
{
    double t = now();
    double every = setup_.timeout > 0 ? std::min(kHeartbeat, setup_.timeout / 4.0) : kHeartbeat;
    if (!busy_ || t - last_beat_ < every)
        return;
    last_beat_ = t;
    Progress p;
    p.unit = job_.unit;
    p.frame = cur_frame_;
    p.done = px_done_;
    p.total = px_total_;
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
        if (child_.fd >= 0)
            fds.push_back({child_.fd, POLLIN, 0});
        poll(fds.data(), nfds_t(fds.size()), 200);

        if (child_.fd >= 0) {
            std::vector<std::string> lines;
            bool open = read_child(child_, lines);
            for (const std::string &l : lines)
                if (busy_)
                    on_line(l);
            if (!open && busy_) {
                int status = 0;
                if (!wait_child(child_, 30, status)) {
                    kill_child(child_);
                    status = SIGKILL;
                }
                renderer_exited(status);
            } else if (!open) {
                kill_child(child_);
            }
        }

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
            case FC_TRUNCATE: on_truncate(); break;
            case FC_CANCEL: on_cancel(); break;
            case FC_PING: break;
            case FC_QUIT: return 0;
            case FC_MASTEREXIT: return 0;
            default: break;
            }
            pvm_freebuf(buf);
        }
        flush_ready(false);
        check_stopping();
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

    Slave slave;
    std::string err;
    if (!slave.init(err)) {
        fprintf(stderr, "fc-slave: %s\n", err.c_str());
        slave.cleanup();
        pvm_exit();
        return 2;
    }
    int rc = slave.run();
    slave.cleanup();
    pvm_exit();
    return rc;
}
