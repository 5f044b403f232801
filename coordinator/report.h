// report.h - what fc-master tells the user: progress while rendering, a per-host summary at
// the end, and the --stats JSON file (per frame and per job: host, rays, time).
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
    double rays = 0, busy = 0;
};

class Report {
public:
    // interval: seconds between plain progress lines (stderr not a terminal); 0 = quiet.
    Report(double interval, bool quiet);

    // Called often; prints when due. fraction in [0,1].
    void progress(double elapsed, int frames_done, int frames_total, double fraction, int busy,
                  int slaves);
    // End a live bar line before other output.
    void clear_line();

    static std::string duration(double seconds);

    std::string summary(double elapsed, int rendered, int resumed, const std::string &division,
                        const std::map<std::string, HostStat> &hosts) const;

    bool write_json(const std::string &path, const std::string &json_head,
                    const std::vector<FrameStat> &frames, const std::map<int, JobStat> &jobs,
                    const std::map<std::string, HostStat> &hosts, std::string &err) const;

    static std::string json_string(const std::string &s);

private:
    bool tty_;
    bool quiet_;
    double interval_;
    double last_ = 0;
    bool bar_open_ = false;
};

} // namespace fc
