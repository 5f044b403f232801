// schedule.h - which slave renders which tiles of which frame: fc-master's bookkeeping, free of
// PVM so it can be tested on its own.
//
// The render area is cut into tiles (one tile, the whole area, for sequence division); the
// animation's frames are addressed by index 0..nframes-1. A cell (frame, tile) is done once its
// pixels reached the master. A job is what a slave renders with one parse: one frame and a set
// of tiles. A slave's renderer walks forward through the frames, so frame coherence keeps its
// state from job to job as long as the slave keeps its tiles.
//
// Frames are grouped into ranges of consecutive frames (Davis & Davis, section 3): sequence
// division gives each slave its own range of whole frames, frame division puts every slave in
// one range and divides each frame's tiles among them, hybrid has a few ranges with a few
// slaves each. In a range with several slaves, each frame's tiles are divided when the first
// of them asks for that frame: the first time dealt out in raster order by speed (so every
// slave has tiles all over the frame and shares its expensive regions, such as the few that
// frame coherence re-traces), later every slave keeps the tiles it had (its renderer's
// coherence).
// Slaves of a range work on neighbouring frames, so frames complete in order and the master
// holds a few frames, not all of them: a range never divides a frame more than kWindow frames
// past its oldest unfinished one. A slave that reaches that limit waits, and the next
// division moves tiles from the slowest to the fastest slaves (by measured speed) until no
// share exceeds its speed's by more than 20%, at most once every kMoveGap frames: with frame
// coherence tiles move only when the slaves really drift apart, since a moved tile costs a
// full re-trace on its new slave (and such a frame does not count in the slave's speed).
// Without fc (set_cheap_moves) no renderer keeps state in its tiles, and what a job costs
// beyond its pixels (a parse and a frame's set-up) is paid once per slave that holds tiles of
// a frame: each frame then goes whole to the slave that would finish it first, while enough
// frames follow to keep the others busy, and the last few frames are dealt afresh in raster
// order, in shares that let the slaves finish together (by speed and by the work each still
// has queued). Whole frames reach the master complete, so the window grows by two frames
// (the jobs each slave has queued) per member.
//
// Load balancing: a slave whose range is finished joins the range with the most work left per
// slave (frame division) or splits it, taking the later part of its undivided frames
// (sequence and hybrid): half without fc; with fc less, since the newcomer's first frame is
// traced in full (set_fresh_cost), and nothing when it could not finish sooner. Jobs are
// handed out at most two per slave ahead, so a split needs no handshake.
// When nothing is left to hand out, an idle slave duplicates the oldest job another slave is
// rendering, once it ran twice as long as jobs take (stragglers); the first result of each
// cell wins and the slower copy is cancelled. A job whose slave has not finished it by its
// deadline (stalled: a stopped or hung renderer or slave, a frame that never ends) gets a copy
// at once, before any other work, on another slave, another host's when there is one; its
// slave gets nothing more (its queued job and its share of the range go to the others) until
// that job is over, either way.
//
// Faults: the cells of a job whose slave died or failed go back to the front of the queue
// (orphans), preferring another host for failed ones; a cell that failed kRetries times
// makes the render fail.
#pragma once

#include <deque>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cell_grid.h"
#include "cost_model.h"
#include "protocol.h"

namespace fc {

enum class Division { Sequence, Frame, Hybrid };

const char *division_name(Division d);
bool parse_division(const std::string &s, Division &d);

// Tiles of at most `size` pixels square covering area, row by row.
std::vector<Rect> make_tiles(const Rect &area, int size);

struct Job {
    int id = 0;
    int index = 0;              // frame index
    std::vector<int> tiles;     // ascending
    int slave = 0;
    int range = -1;             // the range it came from (-1: an orphan or a duplicate)
    int dup_of = -1;            // the job this one duplicates
    bool has_dup = false;
    bool stalled = false;       // its slave has not finished it by its deadline (liveness.h)
    bool live = true;           // handed out, no result yet
    int failures = 0;           // failed attempts of these cells before this one
    double started = 0;         // handed out
    double rendering = -1;      // its slave began it (its previous job was done); -1: queued
};

class Schedule {
public:
    static const int kWindow = 4;   // frames a range may divide beyond its oldest unfinished one
    static const int kRetries = 3;  // failed attempts of a cell before the render fails
    static constexpr double kStragglerSeconds = 1.0;   // a job runs this long before a copy
    static const int kMoveGap = 2 * kWindow;    // frames between two rebalancing moves

    // The schedule reads which cells are done from `cells` (kept by the frame book) and what
    // work costs from `costs` (fed with the results); both outlive it.
    Schedule(const std::vector<Rect> &tiles, const CellGrid &cells, const CostModel &costs,
             Division division);

    int tiles() const { return int(tiles_.size()); }
    int frames() const { return cells_.frames(); }
    const Rect &tile(int t) const { return tiles_[size_t(t)]; }

    // Cut the missing frames into `parts` ranges (sequence, hybrid) or one (frame). A hybrid
    // range is shared by its part of the `slaves` expected (rounded up); a slave beyond that
    // splits a range, as in sequence division.
    void plan(int parts, int slaves = 0);

    // What the costs mean for the work (cost_model.h). Without frame coherence a moved tile
    // costs its new slave nothing extra (cheap moves): then every frame is dealt afresh by
    // speed, not only after a slave had to wait. With frame coherence a renderer's first frame
    // is traced in full and costs fresh_cost coherent frames: a split gives the newcomer as
    // many frames as let both finish together at their measured speeds, and none when it could
    // not finish sooner. In sequence division a renderer that rendered before keeps its
    // samples when it jumps forward to the tail of another range: its first frame there costs
    // jump_cost coherent frames (until one was seen, a jump is priced halfway between a
    // coherent frame and a fresh start). A renderer cannot go back (it ends after the
    // animation's last frame): a tail before a slave's last frame is a fresh start.

    // Slaves: a slave joins when it is ready (host identifies its machine for retries).
    void add_slave(int slave, int host);
    // A slave is gone: its live jobs' missing cells become orphans. Returns those jobs.
    std::vector<int> remove_slave(int slave);

    // The next job for slave, or nullptr when there is nothing for it now.
    const Job *next_job(int slave, double t, bool allow_duplicates);

    // The result of job id for frame index arrived, and its new cells are marked in the grid
    // (a job of a slave that was given up for lost still counts: the first result of a cell
    // wins). Jobs that have nothing left to add are appended to cancel (they are no longer
    // live).
    void job_done(int id, int index, std::vector<Job> &cancel, double t);

    // A job failed on its slave (not a scene error), or was abandoned there: its missing
    // cells become orphans that avoid that host. Returns the largest failure count of those
    // cells.
    int job_failed(int id, double t);

    // Job id did not finish by its deadline: it gets a copy on the next slave that asks (not
    // its own), and its slave is suspended: its queued jobs are taken back (appended to
    // cancel, their cells orphans) and it leaves its range.
    void stall(int id, std::vector<Job> &cancel);
    // Whether slave is suspended: it gets no work.
    bool suspended(int slave) const;
    // Every suspended slave.
    std::set<int> suspended_slaves() const;
    // The slave spoke: its suspension ends once its stalled job is over (a result, a failure,
    // a cancel it confirmed), since a slave that is stopped itself says nothing. Returns
    // whether it was suspended and is no longer.
    bool resume(int slave);

    // Frame index needs no more work (its cells are done: given up, skipped): its live jobs
    // are appended to cancel.
    void frame_settled(int index, std::vector<Job> &cancel, double t);

    const Job *find(int id) const;
    const std::map<int, Job> &jobs() const { return jobs_; }
    int live_jobs(int slave) const;
    size_t orphans() const { return orphans_.size(); }

    // Restore the invariant "every missing cell is covered by a live job, a range's
    // undivided frames or an orphan" if it ever broke: returns the cells queued again.
    int repair();

private:
    struct Range {
        int lo = 0, hi = 0;             // frame indices, inclusive; hi shrinks when split
        int frontier = 0;               // first index not divided among the members yet
        int oldest = 0;                 // no frame before it is unfinished (only grows)
        std::vector<int> members;
        std::map<int, std::map<int, std::vector<int>>> reserved;   // index -> slave -> tiles
        std::map<int, int> owner;       // tile -> slave that had it last
        bool lagging = false;           // a member waited for the others: rebalance
        int last_move = -1000;          // index of the last division that moved tiles
    };
    struct SlaveState {
        int host = 0;
        int range = -1;
        int cursor = 0;                 // next index it takes in its range
        int last = -1;                  // the latest frame index it was given (-1: none yet)
        bool suspended = false;         // a job of it stalled: no work until it speaks
    };
    struct Orphan {
        int index = 0;
        std::vector<int> tiles;
        int failures = 0;
        std::set<int> avoid_hosts;
    };

    bool done(int index, int tile) const { return cells_.done(index, tile); }
    bool frame_done(int index) const { return cells_.frame_done(index); }
    bool finished() const { return cells_.all_done(); }
    void prune();
    void next_rendering(int slave, double t);
    int add_job(int slave, int index, const std::vector<int> &tiles, int range, double t);
    const Job *take_orphan(int slave, double t);
    const Job *take_stalled(int slave, double t);
    const Job *take_from_range(int slave, double t);
    bool find_range(int slave);
    int split_take(const Range &r, int slave) const;   // frames a split of r would give slave
    bool jumps_forward(const Range &r, const SlaveState &s) const; // keeps its samples for r
    double unmeasured_jump_cost() const;                // a forward jump's price before one is seen
    const Job *duplicate(int slave, double t);
    void divide(int r, int index, double when);
    bool whole_frames(const Range &r, int index, const std::map<int, double> &speed) const;
    std::map<int, double> seconds_until_free(const Range &r, int index, double when,
                                             const std::map<int, double> &speed) const;
    std::map<int, double> member_speeds(const Range &r) const;
    int window(const Range &range) const;
    void finish_together(const Range &r, int index, double when, double area,
                         const std::map<int, double> &speed,
                         std::map<int, double> &target) const;
    void leave_range(int slave);
    void orphan(int index, const std::vector<int> &tiles, int failures, int avoid_host);
    std::vector<int> missing(int index, const std::vector<int> &tiles) const;
    int oldest_unfinished(Range &range) const;
    long range_work(const Range &range) const;

    std::vector<Rect> tiles_;
    const CellGrid &cells_;
    const CostModel &costs_;
    Division division_;
    std::vector<Range> ranges_;
    std::map<int, SlaveState> slaves_;
    int hybrid_members_ = 1;            // slaves a hybrid range takes before it is split
    std::deque<Orphan> orphans_;
    std::map<int, Job> jobs_;
    int next_id_ = 1;
};

} // namespace fc
