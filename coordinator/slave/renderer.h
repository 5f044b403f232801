// renderer.h - one povray-fc process, driven frame by frame through its frame control and
// read through its frame channel (frame-channel/ has both formats).
//
// The process is started at some frame of the animation and walks forward: before each frame
// it waits for a control line, so one process renders many jobs (a frame and a set of
// rectangles each) with one parse per frame, and frame coherence carries its state from job
// to job. A job for an earlier frame needs a fresh process. Rectangles the last frame did not
// cover need none: fc forgets the blocks a frame left out (they missed its changes) and
// traces them in full when they come back. The console output is kept only to explain
// failures, so it does not wake the slave unless the scene fills it quickly.
#pragma once

#include <sys/types.h>

#include <deque>
#include <string>
#include <vector>

#include "child_process.h"
#include "frame-channel/control_line.h"
#include "frame-channel/frame_record.h"
#include "protocol.h"

namespace fc {

struct RendererConfig {
    std::string program;                // absolute path of povray-fc
    std::string cwd;
    std::vector<std::string> options;   // the user's POV-Ray options, then ours (extra)
    std::vector<std::string> extra;
    std::string workdir;                // private, writable directory (output name lives here)
    int threads = 1;
    int nice = 0;
    bool animated = true;
    int last_frame = 0;                 // last frame of the animation subset (+EF)
    bool coherent = false;              // frame coherence on: rectangle sets may only shrink
};

// Why a renderer stopped working.
struct RendererFailure {
    bool scene_error = false;           // POV-Ray reported an error in the scene (fatal)
    int status = -1;                    // wait status, -1 if it did not exit
    std::string message;                // POV-Ray's error lines, or what went wrong
};

class Renderer {
public:
    enum State { Stopped, Waiting, Busy };

    ~Renderer() { kill(); }

    // Start a process that renders frames from `first` on; it waits for a job.
    bool start(const RendererConfig &config, int first, std::string &err);

    State state() const { return state_; }
    int frame() const { return frame_; }
    // The frame being rendered is this process's first, or (with fc) has rectangles the last
    // one did not: fc traces those in full, so the frame says nothing of fc's speed.
    bool fresh_frame() const { return fresh_frame_; }

    // Whether this process can render frame `frame` (over any rectangles) without starting over.
    bool can_take(int frame) const;

    // Ask the waiting process to render frame over rects (can_take must hold). False when it
    // has ended meanwhile: `failure` says why, as pump() would (killed, crashed...).
    bool submit(int frame, const std::vector<Rect> &rects, RendererFailure &failure);

    // File descriptors to poll for input: the channel, and the console while it is chatty
    // (pump reads it whatever woke the caller).
    void poll_fds(std::vector<int> &fds) const;

    // Read what arrived. Finished frames are appended to done (the process is Waiting again);
    // returns false when the process failed or exited while Busy, with failure filled in, or
    // exited unexpectedly in any state (then it is Stopped).
    bool pump(std::vector<FrameRecord> &done, RendererFailure &failure);

    // POV-Ray's last console lines (its error lines when it printed any), for a job that is
    // abandoned because it never finished.
    std::string last_words();

    // End the process: "stop" when it waits (it exits by itself), otherwise kill it.
    void stop();
    void kill();

    pid_t pid() const { return child_.pid; }

private:
    bool fail(RendererFailure &failure, bool scene_error, int status, const std::string &msg);
    void classify_exit(int status, RendererFailure &failure);
    // The process has ended (its console, channel or control pipe closed): reap it, keep its
    // last console lines, and say whether it failed (into `failure`); `busy`: it had a frame.
    bool collect_exit(bool busy, RendererFailure &failure);

    RendererConfig config_;
    Child child_;                       // console output on child_.fd
    int channel_ = -1;                  // frame records from the renderer
    int control_ = -1;                  // control lines to the renderer
    FrameRecordReader reader_;
    State state_ = Stopped;
    int frame_ = 0;                     // the frame being rendered (Busy) or last asked for
    int next_ = 0;                      // frames below this have passed
    std::vector<Rect> rects_;           // rectangles of the last frame asked for
    bool rendered_any_ = false;
    bool fresh_frame_ = false;
    std::deque<std::string> tail_;      // last console lines
    bool console_polled_ = false;       // the console wakes the slave (renderer.cpp says when)
    size_t console_bytes_ = 0;          // console bytes read since the last frame record
};

} // namespace fc
