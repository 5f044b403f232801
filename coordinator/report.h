// report.h - what fc-master tells the user: progress while rendering, a per-host summary at
// the end, and the --stats JSON file (per frame and per work unit: host, rays, time).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "protocol.h"

namespace fc {

struct CellStat {               // one tile of one frame, as it was accepted
    int tile = 0;
    int unit = 0;
    std::string host;
    double rays = 0, seconds = 0;
};

struct FrameStat {
    int frame = 0;
    std::string file;
    bool resumed = false;       // already in the output directory, not rendered
    double finished_at = -1;    // seconds after start when written
    std::vector<CellStat> cells;
};

struct UnitStat {
    int id = 0, tile = 0;
    Rect rect;
    int first = 0, last = 0;    // frames (last as finally rendered)
    std::string host;
    int tid = 0;
    int dup_of = -1;
    std::string status = "running";
    int frames = 0;             // FC_FRAME messages received
    double rays = 0, seconds = 0;
    double started = 0;
};

struct HostStat {
    std::string name;
    int slaves = 0, units = 0;
    int frames = 0;             // distinct frames it rendered pixels of (FC_FRAME count until the end)
    int tiles = 0;              // FC_FRAME results (frame x tile), duplicates included
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
                    const std::vector<FrameStat> &frames, const std::map<int, UnitStat> &units,
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
