// renderer.cpp - one povray-fc process driven through frame control, read through its frame
// channel.
#include "renderer.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

#include "debug_log.h"
#include "files.h"
#include "povray_console.h"
#include "text.h"

namespace fc {

namespace {

const size_t kTailLines = 60;       // console lines kept to explain a failure
// Console bytes in one frame from which the console is polled (a quarter of a pipe's 64 KB).
const size_t kChattyConsole = 16384;
const int kChannelFd = 3;           // the renderer's frame channel, as it sees it
const int kControlFd = 4;           // its frame control

// Options that make the renderer a pure frame source: no display, no pause, no shell-outs
// (the master runs those once, as one POV-Ray process would), output only to the channel.
// No render (options) or statistics streams on the console: about 80 lines a frame, 90% of
// what the renderer wrote, read only into the tail that explains a failure (warnings and
// errors, which do explain failures, stay). The frame records carry the rays.
std::vector<std::string> slave_options(const RendererConfig &c, int first)
{
    std::vector<std::string> o = {"-D", "-P", "-UA", "-GR", "-GS", "+O" + c.workdir + "/f",
                                  strf("Frame_Channel=/dev/fd/%d", kChannelFd),
                                  strf("Frame_Control=/dev/fd/%d", kControlFd)};
    for (const char *cmd : kShelloutOptions)
        o.push_back(std::string(cmd) + "=");
    if (c.animated) {
        o.push_back(strf("+SF%d", first));
        o.push_back(strf("+EF%d", c.last_frame));
    }
    return o;
}

} // namespace

bool Renderer::start(const RendererConfig &config, int first, std::string &err)
{
    kill();
    config_ = config;
    int chan[2], ctl[2];
    if (pipe2(chan, O_CLOEXEC) != 0)
        return sys_fail(err, "pipe2");
    if (pipe2(ctl, O_CLOEXEC) != 0) {
        close(chan[0]);
        close(chan[1]);
        return sys_fail(err, "pipe2");
    }
    // The thread count goes first, so that the user's +WT overrides it; the format the master
    // resolved comes with its extra options, after the user's.
    std::vector<std::string> argv = {config.program, strf("+WT%d", std::max(1, config.threads))};
    argv.insert(argv.end(), config.options.begin(), config.options.end());
    argv.insert(argv.end(), config.extra.begin(), config.extra.end());
    std::vector<std::string> ours = slave_options(config, first);
    argv.insert(argv.end(), ours.begin(), ours.end());
    // SCHED_BATCH: POV-Ray's threads hand every frame's work to each other (front end, parser,
    // view, render threads: about 150 hand-offs a frame), and on a processor that is busy, as a
    // slave's is, each wake-up preempted the waker and cost two context switches. A batch
    // task's wake-ups wait for the tick instead (the master and slave still preempt it):
    // pinned to one processor, a renderer's fixed cost per frame fell from 1.18 to 0.87 ms
    // and its switches from 152 to 37 a frame; docs/history.md, "2026-12-05 (7cb4f0f)".
    bool ok = start_child(argv, config.cwd, config.nice, child_, err,
                          {{kChannelFd, chan[1]}, {kControlFd, ctl[0]}}, true);
    close(chan[1]);
    close(ctl[0]);
    if (!ok) {
        close(chan[0]);
        close(ctl[1]);
        return false;
    }
    channel_ = chan[0];
    control_ = ctl[1];
    fcntl(channel_, F_SETFL, fcntl(channel_, F_GETFL) | O_NONBLOCK);
    reader_ = FrameRecordReader();
    state_ = Waiting;
    frame_ = first;
    next_ = first;
    rects_.clear();
    rendered_any_ = false;
    tail_.clear();
    console_polled_ = true;     // until the first frame has shown how much the scene says
    console_bytes_ = 0;
    debug_log("renderer %d started at frame %d", int(child_.pid), first);
    return true;
}

bool Renderer::can_take(int frame) const
{
    if (state_ != Waiting || frame < next_ || (!config_.animated && rendered_any_))
        return false;
    // Any rectangles: with frame coherence, blocks left out of a frame are forgotten at its
    // end (they missed its changes), so a tile this process gains is traced in full here.
    return true;
}

bool Renderer::submit(int frame, const std::vector<Rect> &rects, RendererFailure &failure)
{
    std::string line = render_control_line(frame, rects);
    const char *p = line.data();
    size_t left = line.size();
    while (left > 0) {
        ssize_t n = write(control_, p, left);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            // The pipe broke because the process ended before pump() saw it: say why it
            // did (a kill, a crash), not only that the pipe broke.
            std::string err;
            sys_fail(err, "write to the renderer's frame control");
            frame_ = frame;
            collect_exit(true, failure);
            if (failure.message.empty())
                failure.message = err;
            return false;
        }
        p += n;
        left -= size_t(n);
    }
    state_ = Busy;
    frame_ = frame;
    next_ = frame + 1;
    // With fc, rectangles the last frame did not cover have no stored samples here.
    fresh_frame_ = !rendered_any_;
    for (const Rect &r : rects)
        fresh_frame_ = fresh_frame_ || (config_.coherent && std::find(rects_.begin(), rects_.end(), r) == rects_.end());
    rects_ = rects;
    rendered_any_ = true;
    return true;
}

// The console is read whenever the slave wakes (every frame's record wakes it), and polled
// only while the scene is chatty: POV-Ray writes its status lines to it in about nine writes
// a frame, and each woke the slave (4-5 wake-ups a frame, 2 without them; fc-slave's CPU
// 15% lower on the emulated cluster). It is polled during a renderer's first frame, and
// after it during every frame that follows one with 16 KB or more of console output (#debug).
// A scene that becomes that chatty later holds its renderer up once, until the slave's poll
// times out (200 ms) and finds the full pipe; from then on the console is polled.
void Renderer::poll_fds(std::vector<int> &fds) const
{
    if (child_.fd >= 0 && console_polled_)
        fds.push_back(child_.fd);
    if (channel_ >= 0)
        fds.push_back(channel_);
}

bool Renderer::fail(RendererFailure &failure, bool scene_error, int status, const std::string &msg)
{
    failure.scene_error = scene_error;
    failure.status = status;
    failure.message = msg;
    kill();
    return false;
}

// A renderer that exited while it had work (or failed a frame): POV-Ray's own error lines
// mean the scene is at fault; anything else (a signal, a missing program, a broken channel)
// is this host's problem.
void Renderer::classify_exit(int status, RendererFailure &failure)
{
    std::vector<std::string> tail(tail_.begin(), tail_.end());
    bool exited = WIFEXITED(status);
    int code = exited ? WEXITSTATUS(status) : -1;
    failure.status = status;
    failure.scene_error = exited && code != 0 && code != 126 && code != 127 &&
                          is_scene_error(tail);
    if (WIFSIGNALED(status)) {
        // Killed (the kernel's out-of-memory killer sends SIGKILL) or crashed: only POV-Ray's
        // own error lines tell more; its progress lines do not.
        std::string excerpt = error_excerpt(tail);
        int sig = WTERMSIG(status);
        failure.message = strf("the renderer was killed by signal %d (%s) during frame %d%s", sig,
                               strsignal(sig), frame_,
                               sig == SIGKILL ? "; out of memory? the kernel's OOM killer sends "
                                                "SIGKILL" : "");
        if (!excerpt.empty())
            failure.message += "\n" + excerpt;
        return;
    }
    std::string excerpt = failure_excerpt(tail);
    failure.message = excerpt.empty() ? strf("the renderer stopped during frame %d (%s)", frame_,
                                             describe_status(status).c_str())
                                      : excerpt;
}

bool Renderer::pump(std::vector<FrameRecord> &done, RendererFailure &failure)
{
    if (state_ == Stopped)
        return true;
    if (child_.fd >= 0) {
        std::vector<std::string> lines;
        read_child(child_, lines);
        for (const std::string &l : lines) {
            console_bytes_ += l.size() + 1;
            tail_.push_back(l);
            if (tail_.size() > kTailLines)
                tail_.pop_front();
        }
        if (console_bytes_ >= kChattyConsole)
            console_polled_ = true;
    }
    bool channel_open = true;
    if (channel_ >= 0) {
        char buf[65536];
        for (;;) {
            ssize_t n = read(channel_, buf, sizeof buf);
            if (n > 0) {
                reader_.feed(buf, size_t(n));
                continue;
            }
            if (n < 0 && errno == EINTR)
                continue;
            if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) {
                close(channel_);
                channel_ = -1;
                channel_open = false;
            }
            break;
        }
        for (;;) {
            FrameRecord rec;
            std::string err;
            int r = reader_.next(rec, err);
            if (r == 0)
                break;
            if (r < 0)
                return fail(failure, false, -1, err);
            if (state_ != Busy || rec.frame != frame_ || rec.rects != rects_)
                return fail(failure, false, -1,
                            strf("the renderer sent frame %d, but frame %d was asked for",
                                 rec.frame, frame_));
            state_ = Waiting;
            done.push_back(std::move(rec));
            console_polled_ = console_bytes_ >= kChattyConsole;
            console_bytes_ = 0;
        }
    } else {
        channel_open = false;
    }
    if (channel_open && child_.fd >= 0)
        return true;
    // Console or channel closed: the process is ending.
    return collect_exit(state_ == Busy, failure);
}

bool Renderer::collect_exit(bool busy, RendererFailure &failure)
{
    int status = 0;
    if (!wait_child(child_, 30, status)) {
        kill_child(child_);
        status = SIGKILL;
    }
    // Drain the console for the error message.
    if (child_.fd >= 0) {
        std::vector<std::string> lines;
        while (read_child(child_, lines)) {
        }
        for (const std::string &l : lines) {
            tail_.push_back(l);
            if (tail_.size() > kTailLines)
                tail_.pop_front();
        }
    }
    kill();
    debug_log("renderer exited: %s, %s", describe_status(status).c_str(), busy ? "busy" : "waiting");
    if (busy || !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        classify_exit(status, failure);
        // A process that ends cleanly while waiting passed its last frame: not a failure.
        return !busy && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    }
    return true;
}

std::string Renderer::last_words()
{
    if (child_.fd >= 0) {
        std::vector<std::string> lines;
        read_child(child_, lines);
        for (const std::string &l : lines) {
            tail_.push_back(l);
            if (tail_.size() > kTailLines)
                tail_.pop_front();
        }
    }
    std::vector<std::string> tail(tail_.begin(), tail_.end());
    std::string words = failure_excerpt(tail);
    return words.empty() ? "(POV-Ray printed nothing)\n" : words;
}

void Renderer::stop()
{
    if (state_ == Waiting && control_ >= 0) {
        static const char line[] = "stop\n";
        ssize_t n = write(control_, line, sizeof line - 1);
        (void)n;
        int status;
        if (wait_child(child_, 2, status)) {
            kill();
            return;
        }
    }
    kill();
}

void Renderer::kill()
{
    kill_child(child_);
    if (channel_ >= 0)
        close(channel_);
    if (control_ >= 0)
        close(control_);
    channel_ = control_ = -1;
    state_ = Stopped;
}

} // namespace fc
