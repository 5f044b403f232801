// master.h - fc-master's state and its parts: set-up and statistics (master_setup.cpp), the
// receive loop and one handler per message (master.cpp).
#pragma once

#include <signal.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "assembly.h"
#include "cluster.h"
#include "command_line.h"
#include "output_dir.h"
#include "output_format.h"
#include "povray_probe.h"
#include "preview.h"
#include "report.h"
#include "schedule.h"
#include "shellout.h"

namespace fc {

// The signal that asks the master to stop (0: none); set by the handler in master.cpp.
extern volatile sig_atomic_t g_signal;
// The handler of SIGINT, SIGTERM and SIGHUP: sets g_signal.
void on_signal(int sig);

class Master {
public:
    Master(const Options &o) : opt_(o), report_(o.progress, o.quiet) {}
    // The whole render; returns the exit status.
    int run();

private:
    // Set-up steps, in order.
    bool resolve_programs();
    bool probe();
    bool choose_format_by_name(ResolvedOptions &ini, double limit, std::string &err);
    bool prepare_output();
    Manifest manifest() const;
    bool resume_frames(bool fresh, bool adopt, std::vector<bool> &replace);
    bool check_space(const std::vector<bool> &replace);
    bool start_cluster();

    // The receive loop and its handlers, one per tag.
    int loop();
    void on_hello(int src);
    void on_frame(int src);
    void on_progress(int src);
    void on_fail(int src);
    void on_task_exit();
    void on_host_delete();
    void on_host_add();

    // Helpers.
    void plan_if_ready();
    void dispatch();
    void send_job(SlaveInfo &s, const Job &job);
    void cancel_jobs(const std::vector<Job> &jobs);
    bool frame_finished(int index);
    void write_complete_frames(bool wait);
    void slave_gone(SlaveInfo &s, const std::string &why, bool respawn);
    void leave_out_host(int dtid, const std::string &last_error);
    void check_timeouts();
    void progress();
    void flush_preview(bool force);
    // Seconds since the loop began, the share of this run's tiles done, and the estimated
    // seconds to go (-1 while too little is done to tell).
    void work_done(double &elapsed, double &fraction, double &eta) const;
    ProgressState progress_state() const;
    RunSummary run_summary(bool ok, double elapsed) const;
    void fatal(const std::string &msg);
    void shutdown_slaves();
    void finish(bool ok);
    int index_of(int frame) const;
    HostStat &host_stat(const std::string &name);

    Options opt_;
    Report report_;
    std::string renderer_, cwd_, outdir_, tmpdir_;
    std::vector<std::string> extra_;    // for the slaves, after the user's: fc on, block size
    std::vector<std::string> format_options_;   // the format when the user named none (+FN)
    SceneInfo scene_;
    ResolvedOptions resolved_;          // POV-Ray's resolved options (Create_Ini)
    OutputFormat format_;
    OutputDir outdir_obj_;              // lock, manifest and journal of the output directory
    Preview preview_;
    Shellouts shellouts_;
    std::vector<Rect> tiles_;
    std::unique_ptr<Schedule> sched_;
    std::unique_ptr<FrameAssembly> assembly_;
    Cluster cluster_;
    bool planned_ = false;
    double start_ = 0, spawn_time_ = 0, next_tick_ = 0;
    bool failed_ = false;
    bool quit_early_ = false;           // a shell-out asked to stop (exit status 0)
    // Frames whose every tile arrived, in order of completion, not yet written: a write
    // waits while OpenImageIO still loads (0.3 s of CPU at the start), and the slaves'
    // replies must not (write_complete_frames).
    std::vector<int> unwritten_;
    bool write_failed_ = false;
    bool skip_post_scene_ = false;      // ... and to skip the rest, Post_Scene included
    int skipped_ = 0;                   // frames a Pre_Frame_Command skipped
    int max_frames_held_ = 0;           // most frames in the master's memory at once
    long messages_ = 0;                 // messages received
    int exit_code_ = 0;
    std::string error_;                 // the first fatal error
    std::string last_failure_;          // the last host-side failure ("on HOST: message")
    Savings savings_;                   // what fc saved (rays and trace time spent so far)
    double fresh_rays_ = 0, fresh_seconds_ = 0, fresh_pixels_ = 0, pixels_traced_ = 0;
    // Frames a renderer rendered after jumping over others (sequence division's splits): not
    // fresh, not coherent with the frame before; and each slave's last frame index.
    double jump_seconds_ = 0, jump_pixels_ = 0;
    std::map<int, int> last_index_;
    std::string vm_kind_ = "none";      // "private" or "running" once started
    int resumed_ = 0, rendered_ = 0;
    long cells_total_ = 0;
    std::vector<char> frame_started_;   // Pre_Frame_Command ran
    std::vector<FrameStat> frame_stats_;
    std::map<int, JobStat> job_stats_;  // only with --stats
    std::map<std::string, HostStat> host_stats_;
    std::map<std::string, std::set<int>> host_frames_;
    std::map<int, int> frame_index_;
    std::map<int, int> job_slave_;      // live job -> slave tid, to cancel it
};

} // namespace fc
