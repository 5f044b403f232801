// liveness.h - whether the work makes progress, judged by the work itself, not by messages: a
// slave that keeps sending its heartbeat while its renderer is stopped or loops forever makes
// none.
//
// A job is stalled when its slave has not finished it within a deadline learned from the run:
// kFactor times the median time of its host's recent jobs (scaled to the job's pixels; a job's
// time is its renderer's parse and trace, as a frame's time in the run's statistics), never
// less than kFloor seconds (the goal is to act within max(10 s, 5 times the median frame),
// and the master looks every 0.25 s); before a job of any host finished, the master's --timeout. A
// renderer's first frame (with frame coherence traced in full) and a copy of another slave's
// job (its renderer starts afresh or jumps) get the fresh-start factor on top. A stalled job
// gets a copy on another slave (schedule.h).
//
// A frame hangs (it is given up, with POV-Ray's last words) only when a second attempt has
// not finished within the hang deadline: kHangFactor times the expected time, never less
// than kHangFloor. A slow frame and an endless one look alike from outside (a #while loop
// keeps the parser's token count growing), so the first deadline only buys a copy, and a
// frame many times slower than the others but finite still completes.
#pragma once

#include <cstddef>
#include <deque>
#include <map>
#include <set>

namespace fc {

class Liveness {
public:
    static constexpr double kFloor = 8.0;       // seconds: no deadline is shorter
    // Times the host's median job. Early in a run jobs are slower than the run's median (the
    // master's image writer and OpenImageIO load beside the first renderers): 4 times the
    // early median came within 1% of the goal's 5 times the run's median frame.
    static constexpr double kFactor = 3.5;
    static const size_t kHistory = 31;          // recent jobs per host
    static constexpr double kHangFloor = 60.0;  // seconds: no frame hangs sooner
    static constexpr double kHangFactor = 20.0; // times the host's median job

    // fallback: the deadline before any job finished (the master's --timeout).
    explicit Liveness(double fallback) : fallback_(fallback) {}

    // A job of `pixels` on host took `seconds` (its renderer's parse and trace); slave has now
    // delivered a result.
    void job_took(int slave, int host, double pixels, double seconds);

    // The deadline of a job of `pixels` on host, begun by slave; copy: it copies another
    // slave's job. fresh_cost: a fresh start in coherent frames (cost_model.h).
    double deadline(int slave, int host, double pixels, bool copy, double fresh_cost) const;

    // The deadline of a second attempt at a frame that stalled once (its verdict: it hangs).
    double hang_deadline(int host, double pixels) const;

    // The median seconds a pixel took on host (its recent jobs; else on every host; 0: none).
    double seconds_per_pixel(int host) const;

private:
    double fallback_;
    std::map<int, std::deque<double>> per_host_;    // seconds a pixel of recent jobs
    std::deque<double> all_;
    std::set<int> delivered_;                       // slaves with a result
};

} // namespace fc
