// schedule.h - which slave renders which (tile, frame range): the work-unit bookkeeping of
// fc-master, kept free of PVM so it can be tested on its own.
//
// The image is cut into tiles (one tile = the whole render area for sequence division); the
// animation is a list of frames addressed by index 0..nframes-1. A cell (tile, index) is done
// once its pixels reached the master. A work unit covers one tile over a consecutive index
// range [lo, hi] and is run by one POV-Ray process. Invariant: every cell that is not done is
// covered by at least one live unit (queued or running); only straggler duplicates cover a
// cell twice.
//
// Load balancing (Davis & Davis, section 3): when a slave runs dry and nothing is queued, the
// running unit with the most remaining work is split: its slave is asked to stop at the middle
// of what it has left (FC_TRUNCATE), and the tail goes to the idle slave. When nothing can be
// split, an idle slave duplicates the oldest running unit; the first result of a cell wins and
// the slower copy is cancelled once everything it has left is done.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "protocol.h"

namespace fc {

enum class Division { Sequence, Frame, Hybrid };

const char *division_name(Division d);
bool parse_division(const std::string &s, Division &d);

// Tiles of at most `size` pixels square covering area, row by row.
std::vector<Rect> make_tiles(const Rect &area, int size);

struct Unit {
    int id = 0;
    int tile = 0;
    int lo = 0, hi = 0;         // frame indices, inclusive; hi shrinks when truncated
    int next = 0;               // first index this unit has not returned yet
    int slave = 0;              // tid running it; 0 while queued
    int dup_of = -1;            // the unit this one duplicates, -1 if none
    bool has_dup = false;       // a duplicate of this unit is live
    bool truncating = false;    // FC_TRUNCATE sent, FC_TRUNCATED not yet received
    int reserved = 0;           // idle slave waiting for this unit's tail
    bool cancelling = false;    // FC_CANCEL sent
    bool no_split = false;      // its slave left an FC_TRUNCATE unanswered: only duplicate it
    bool live = true;           // queued or running
    double started = 0;         // when it was handed out
    int remaining() const { return hi - next + 1; }
};

struct Action {
    enum Kind { None, Run, Split } kind = None;
    int unit = -1;              // Run: the unit now assigned; Split: the unit to truncate
    int new_hi = 0;             // Split: ask its slave to stop after this index
};

class Schedule {
public:
    Schedule(const std::vector<Rect> &tiles, int nframes);

    int tiles() const { return int(tiles_.size()); }
    int frames() const { return nframes_; }
    const Rect &tile(int t) const { return tiles_[size_t(t)]; }

    // Resume: a cell that is already done needs no work.
    void mark_done(int tile, int index);
    bool done(int tile, int index) const;
    bool frame_done(int index) const { return frame_cells_[size_t(index)] == tiles(); }
    int frames_done() const { return frames_done_; }
    bool finished() const { return frames_done_ == nframes_; }

    // Fill the queue with every missing cell: sequence = `parts` consecutive frame ranges,
    // frame = every tile over the whole range, hybrid = `parts` ranges x every tile.
    void plan(Division division, int parts);

    // What idle slave tid does now. Run: the unit is assigned to tid (popped from the queue,
    // or a new straggler duplicate). Split: send FC_TRUNCATE(unit, new_hi) to the unit's
    // slave; tid is reserved for the tail (see truncated()).
    Action next_for(int tid, double t, bool allow_duplicates);

    // A cell arrived from unit `unit`. Returns true if it is new (store its pixels), false
    // for a duplicate. Units that have nothing left to do are appended to cancel.
    bool frame_arrived(int unit, int index, std::vector<int> &cancel);

    // The unit's slave answered FC_TRUNCATE, it stops after index accepted (-1: not
    // running). Returns the tail unit id (-1 if none) and sets reserved to the slave that was
    // waiting for it (0 if none); the caller assigns the tail with assign() or leaves it queued.
    int truncated(int unit, int accepted, int &reserved);

    // The unit's slave did not answer FC_TRUNCATE in time: forget the request (a late answer
    // is ignored, its tail then comes back through unit_ended) and never split it again.
    // Returns the slave that was reserved for the tail (0 if none).
    int truncate_timed_out(int unit);

    // The unit ended (finished, cancelled, truncated, or its slave died). Its cells that are
    // neither done nor covered by another live unit go back to the front of the queue.
    // Returns a slave that was reserved for this unit's tail (0 if none): it is idle again.
    int unit_ended(int unit);

    // Queue every missing cell that no live unit covers (restores the invariant; returns the
    // number of units added, 0 when it held).
    int repair();

    // Hand queued unit to slave tid.
    void assign(int unit, int tid, double t);

    Unit &unit(int id) { return units_.at(id); }
    const Unit *find(int id) const;
    const std::map<int, Unit> &units() const { return units_; }
    size_t queued() const { return queue_.size(); }
    int running() const;

private:
    int add_unit(int tile, int lo, int hi, bool front);
    bool covered(int tile, int index, int except) const;
    bool all_done(int tile, int lo, int hi) const;

    std::vector<Rect> tiles_;
    int nframes_;
    std::vector<char> done_;            // tile-major: done_[tile * nframes + index]
    std::vector<int> frame_cells_;      // done cells per frame index
    int frames_done_ = 0;
    std::map<int, Unit> units_;
    std::deque<int> queue_;
    int next_id_ = 1;
};

} // namespace fc
