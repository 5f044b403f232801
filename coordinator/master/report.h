// report.h - what fc-master tells the user: progress while rendering, a summary at the end,
// and the --stats JSON file (per frame and per job: host, rays, time).
//
// Progress counts only the work of this run (frames already in the output directory are
// neither done work nor part of the ETA), and never says 100% before the last frame is
// written. On a terminal (stderr) it is a block of lines redrawn in place, each cut to the
// terminal's width (COLUMNS, else TIOCGWINSZ, else 80): a bar with frames and ETA, the frames
// in flight, then one line per host with its throughput. Otherwise a plain line every
// --progress seconds.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "protocol.h"

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
    std::string status = "running";     // done, cancelled, lost, failed, stopped
    double rays = 0, parse = 0, trace = 0;
    double started = 0;
};

struct HostStat {
    std::string name;
    int slaves = 0, jobs = 0;
    int frames = 0;             // distinct frames it rendered pixels of
    int tiles = 0;              // tiles of frames it delivered, duplicates included
    int failures = 0;
    bool excluded = false;
    bool alive = true;          // still in the virtual machine
    double rays = 0, busy = 0;
    double pixels = 0;          // pixels delivered this run (duplicates included)
};

// What frame coherence saved, estimated from the renderers' first frames (which fc traces in
// full): rays and trace seconds per pixel there, times every pixel rendered, against what was
// spent. The rays are those a render without fc traces (fc is exact); the seconds are an upper
// bound, since a first frame also records every ray.
struct Savings {
    bool known = false;
    double rays_spent = 0, rays_full = 0;
    double seconds_spent = 0, seconds_full = 0;
};

// One host's line of the progress display.
struct HostProgress {
    std::string name;
    int slaves = 0, busy = 0;           // live slaves, and those with work
    double pixels = 0;                  // pixels delivered this run
};

// One progress display.
struct ProgressState {
    double elapsed = 0, eta = -1;
    int frames_done = 0, frames_todo = 0, resumed = 0;
    double fraction = 0;                // of this run's work
    std::vector<int> in_flight;         // frames being rendered
    int busy = 0, slaves = 0;
    double frame_pixels = 1;            // pixels of one frame's render area
    std::vector<HostProgress> hosts;    // the live ones
};

// The end of a run.
struct RunSummary {
    bool ok = true;
    std::string error;                  // the first fatal error, when !ok
    double elapsed = 0;
    int rendered = 0, resumed = 0, retried = 0, lost = 0, total = 0, skipped = 0;
    std::string division;
    std::string virtual_machine;        // "private" or "running"
    std::vector<double> frame_seconds;  // per rendered frame, in frame order
    std::vector<int> frame_numbers;
    Savings savings;
    std::map<std::string, HostStat> hosts;
};

class Report {
public:
    // interval: seconds between plain progress lines (stderr not a terminal).
    Report(double interval, bool quiet);

    // Called often; prints when due.
    void progress(const ProgressState &p);
    // Erase the live display before other output.
    void clear_line();

    static std::string duration(double seconds);

    // Columns of the terminal on stderr: COLUMNS, else TIOCGWINSZ, else 80.
    static int terminal_columns();

    // The lines of the live display for a terminal of `columns` (each shorter than that).
    static std::vector<std::string> display(const ProgressState &p, int columns, int rows);
    // The plain progress line.
    static std::string plain_line(const ProgressState &p);

    std::string summary(const RunSummary &s) const;

    bool write_json(const std::string &path, const std::string &json_head,
                    const std::vector<FrameStat> &frames, const std::map<int, JobStat> &jobs,
                    const std::map<std::string, HostStat> &hosts, std::string &err) const;

    static std::string json_string(const std::string &s);

private:
    bool tty_;
    bool quiet_;
    double interval_;
    double last_ = -1e9;
    int lines_open_ = 0;        // lines of the live display on the screen
};

} // namespace fc
