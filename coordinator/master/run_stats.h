// run_stats.h - what happened in a run, per frame, per job and per host: counted as results
// arrive (O(1) a message), read by the progress display and the end summary (report.h), and
// written as the --stats JSON file, which this file alone builds.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "cost_model.h"
#include "protocol.h"
#include "schedule.h"

namespace fc {

struct CellStat {               // one tile of one frame, as it was accepted
    int tile = 0;
    int job = 0;
    std::string host;
};

struct FrameStat {
    int frame = 0;
    std::string file;
    bool resumed = false;       // already in the output directory, not rendered
    bool retried = false;       // one of its jobs failed or was lost and ran again
    double finished_at = -1;    // seconds after start when written
    double rays = 0, seconds = 0;   // of the jobs whose tiles were accepted
    int parses = 0;             // jobs (one parse each) that contributed tiles
    std::vector<CellStat> cells;
};

struct JobStat {
    int id = 0, frame = 0;
    std::vector<int> tiles;
    std::string host;
    int tid = 0;
    int dup_of = -1;
    std::string status = "running";     // done, duplicate, cancelled, lost, failed, stopped
    double rays = 0, parse = 0, trace = 0;
};

struct HostStat {
    std::string name;
    int slaves = 0, jobs = 0;
    int frames = 0;             // distinct frames it rendered pixels of
    int tiles = 0;              // tiles of frames it delivered, duplicates included
    int failures = 0;
    bool excluded = false;
    double rays = 0, busy = 0;
    double pixels = 0;          // pixels delivered this run (duplicates included)
};

// What the statistics say of the run as a whole, given at the end.
struct RunFacts {
    std::string scene, renderer, output;
    Division division = Division::Frame;
    int tile = 0, width = 0, height = 0;
    std::vector<Rect> tiles;
    bool frame_coherence = false;
    std::string virtual_machine = "none";   // "private" or "running" once started
    std::string format;
    int bits_per_color = 8;
    bool ok = true;
    std::string error;                      // the first fatal error, when !ok
    double elapsed = 0;
    int total = 0, rendered = 0, resumed = 0, skipped = 0;
    std::vector<std::pair<int, std::string>> given_up;     // frame numbers, and why
    Savings savings;
};

// The end summary's numbers (report.h prints them).
struct RunSummary {
    bool ok = true;
    std::string error;
    double elapsed = 0;
    int rendered = 0, resumed = 0, retried = 0, lost = 0, total = 0, skipped = 0;
    std::string division;
    std::string virtual_machine;
    std::vector<double> frame_seconds;  // per rendered frame, in frame order
    std::vector<int> frame_numbers;
    std::vector<std::pair<int, std::string>> given_up;     // --keep-going: frames without a file
    Savings savings;
    std::map<std::string, HostStat> hosts;
};

class RunStats {
public:
    // keep_jobs: keep a record of every job (only for --stats; the rest is always counted).
    explicit RunStats(bool keep_jobs) : keep_jobs_(keep_jobs) {}

    // The frames of the run: their numbers and file names.
    void set_frames(const std::vector<int> &numbers, const std::vector<std::string> &files);

    void message_received() { messages_++; }
    void frames_held(size_t n);
    void slaves_started(const std::string &host, int count);
    void host_failed(const std::string &host);
    void host_left_out(const std::string &host);

    void frame_resumed(int index) { frames_[size_t(index)].resumed = true; }
    void frame_retried(int index) { frames_[size_t(index)].retried = true; }
    void frame_written(int index, double seconds_after_start);

    void job_sent(const Job &job, int frame, const std::string &host, int tid);
    // A job ended without a result: "cancelled", "lost", "failed".
    void job_ended(int id, const char *status);
    // A result of job fr.job from host, for frame index; fresh: the tiles it was first with.
    void result(const FrameResult &fr, int index, const std::vector<int> &fresh,
                const std::string &host);

    const std::map<std::string, HostStat> &hosts() const { return hosts_; }
    double host_pixels(const std::string &host) const;

    RunSummary summary(const RunFacts &facts) const;
    // The --stats JSON file, written under a temporary name and renamed. False with err.
    bool write_json(const std::string &path, const RunFacts &facts, std::string &err) const;

private:
    HostStat &host(const std::string &name);
    int frames_retried() const;
    std::string json(const RunFacts &facts) const;

    bool keep_jobs_;
    long messages_ = 0;
    int max_frames_held_ = 0;
    std::vector<FrameStat> frames_;
    std::map<int, JobStat> jobs_;
    std::map<std::string, HostStat> hosts_;
    std::map<std::string, std::set<int>> host_frames_;
};

} // namespace fc
