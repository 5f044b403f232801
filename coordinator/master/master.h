// master.h - fc-master: one render of an animation on the hosts of a PVM virtual machine.
//
// Its parts, each with one job: the plan (render_plan.h: programs, POV-Ray's answers, tiles),
// the output directory and its frames (output_dir.h, frame_files.h), every frame of the run
// (frame_book.h: cells, pixels, order, writing), what work costs (cost_model.h), who renders
// what (schedule.h), the hosts and slaves (cluster.h), the run's statistics (run_stats.h), the
// display (report.h) and the preview (preview.h). The Master holds them and runs the receive
// loop (master.cpp) between the set-up and the end (master_setup.cpp).
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cluster.h"
#include "command_line.h"
#include "cost_model.h"
#include "frame_book.h"
#include "frame_encoder.h"
#include "frame_files.h"
#include "frame_inputs.h"
#include "liveness.h"
#include "output_dir.h"
#include "preview.h"
#include "render_plan.h"
#include "report.h"
#include "run_stats.h"
#include "schedule.h"

namespace fc {

class Master {
public:
    explicit Master(const Options &o)
        : opt_(o), report_(o.progress, o.quiet), stats_(!o.stats.empty()), liveness_(o.timeout)
    {
    }
    // The whole render; returns the exit status.
    int run();

private:
    // Set-up and end (master_setup.cpp).
    bool set_up();
    bool start_cluster();
    void finish(bool ok);
    RunFacts facts(bool ok, double elapsed) const;

    // The receive loop and its handlers, one per tag (master.cpp).
    int loop();
    void on_hello(int src);
    void on_frame(int src);
    void on_progress(int src);
    void on_fail(int src);
    void on_task_exit();
    void on_host_delete();
    void on_host_add();

    // Work (master.cpp).
    void plan_if_ready();
    void dispatch();
    bool run_pre_frame(const Job &job);
    void send_job(SlaveInfo &s, const Job &job);
    void cancel_jobs(const std::vector<Job> &jobs);
    void note_inputs(int index, const FrameResult &fr, const std::string &host);
    void write_complete_frames(bool wait);
    bool frame_written(int index, std::vector<uint8_t> &samples);
    void slave_gone(SlaveInfo &s, const std::string &why, bool respawn);
    void leave_out_host(int dtid, const std::string &last_error);
    void check_timeouts();
    void tick();

    // Liveness (master_liveness.cpp): stalled jobs, frames that hang or keep failing.
    void check_stalls();
    void job_stalled(const Job &job, double seconds, double deadline);
    // Whether job began after a job of its frame stalled: a copy or a re-render.
    bool second_attempt(const Job &job) const;
    void frame_hangs(int index);
    void abandon(const Job &job);
    void on_abandoned(const Failure &f, const std::string &host);
    void conclude_hangs(bool all);
    void give_up_frame(int index, const std::string &why);

    // What the user sees (master.cpp).
    void warn(const std::string &message);
    void tell(const ShelloutResult &r);
    void progress();
    void flush_preview(bool force);
    // Seconds since the loop began, the share of this run's tiles done, and the estimated
    // seconds to go (-1 while too little is done to tell).
    void work_done(double &elapsed, double &fraction, double &eta) const;
    ProgressState progress_state() const;
    void fatal(const std::string &msg);
    void shutdown_slaves();
    void kill_local_slave(int tid);

    Options opt_;
    RenderPlan plan_;
    Report report_;
    OutputDir outdir_;                  // lock, manifest and record of the output directory
    std::unique_ptr<FrameEncoder> encoder_;
    std::unique_ptr<FrameFiles> files_;
    std::unique_ptr<FrameBook> book_;   // every frame: cells, pixels, order, writing
    CostModel costs_;
    std::unique_ptr<Schedule> sched_;
    Cluster cluster_;
    Preview preview_;
    RunStats stats_;
    InputHashes hashes_;                // the frames' input files' contents
    Liveness liveness_;
    // Frames found hanging: their jobs are abandoned, and POV-Ray's last words awaited.
    struct Hang {
        std::set<int> jobs;             // abandoned jobs whose last words are awaited
        std::vector<std::string> hosts;
        std::string words;
        double until = 0;               // no longer
    };
    std::map<int, Hang> hangs_;         // by frame index

    bool planned_ = false;              // the frames are cut into ranges
    double start_ = 0, spawn_time_ = 0, next_tick_ = 0;
    bool failed_ = false;
    bool quit_early_ = false;           // a shell-out asked to stop (exit status 0) ...
    bool skip_post_scene_ = false;      // ... and to skip the rest, Post_Scene included
    bool write_failed_ = false;
    int exit_code_ = 0;
    std::string error_;                 // the first fatal error
    std::string last_failure_;          // the last host-side failure ("on HOST: message")
};

} // namespace fc
