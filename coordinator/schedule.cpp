// schedule.cpp - work-unit bookkeeping: plan, hand out, split, duplicate, re-queue.
#include "schedule.h"

#include <algorithm>
#include <cassert>

namespace fc {

const char *division_name(Division d)
{
    switch (d) {
    case Division::Sequence: return "sequence";
    case Division::Frame: return "frame";
    case Division::Hybrid: return "hybrid";
    }
    return "?";
}

bool parse_division(const std::string &s, Division &d)
{
    if (s == "sequence") d = Division::Sequence;
    else if (s == "frame") d = Division::Frame;
    else if (s == "hybrid") d = Division::Hybrid;
    else return false;
    return true;
}

std::vector<Rect> make_tiles(const Rect &area, int size)
{
    std::vector<Rect> tiles;
    for (int y = area.y0; y < area.y1; y += size)
        for (int x = area.x0; x < area.x1; x += size)
            tiles.push_back(Rect{x, y, std::min(area.x1, x + size), std::min(area.y1, y + size)});
    return tiles;
}

Schedule::Schedule(const std::vector<Rect> &tiles, int nframes)
    : tiles_(tiles), nframes_(nframes),
      done_(tiles.size() * size_t(nframes), 0), frame_cells_(size_t(nframes), 0)
{
}

void Schedule::mark_done(int tile, int index)
{
    char &d = done_[size_t(tile) * size_t(nframes_) + size_t(index)];
    if (d)
        return;
    d = 1;
    if (++frame_cells_[size_t(index)] == tiles())
        frames_done_++;
}

bool Schedule::done(int tile, int index) const
{
    return done_[size_t(tile) * size_t(nframes_) + size_t(index)] != 0;
}

bool Schedule::all_done(int tile, int lo, int hi) const
{
    for (int i = lo; i <= hi; i++)
        if (!done(tile, i))
            return false;
    return true;
}

int Schedule::add_unit(int tile, int lo, int hi, bool front)
{
    Unit u;
    u.id = next_id_++;
    u.tile = tile;
    u.lo = lo;
    u.hi = hi;
    u.next = lo;
    units_[u.id] = u;
    if (front)
        queue_.push_front(u.id);
    else
        queue_.push_back(u.id);
    return u.id;
}

void Schedule::plan(Division division, int parts)
{
    parts = std::max(1, parts);
    // Runs of frame indices with some cell missing (all tiles agree after a resume, which
    // works on whole frames; per-tile runs are cut below).
    std::vector<std::pair<int, int>> runs;
    for (int i = 0; i < nframes_; i++) {
        if (frame_done(i))
            continue;
        if (!runs.empty() && runs.back().second == i - 1)
            runs.back().second = i;
        else
            runs.push_back({i, i});
    }
    int missing = 0;
    for (auto &r : runs)
        missing += r.second - r.first + 1;

    // Cut the runs into ranges of about missing/parts frames (a range never spans a gap).
    std::vector<std::pair<int, int>> ranges;
    if (division == Division::Frame) {
        ranges = runs;
    } else {
        int target = std::max(1, (missing + parts - 1) / parts);
        for (auto &r : runs)
            for (int lo = r.first; lo <= r.second; lo += target)
                ranges.push_back({lo, std::min(r.second, lo + target - 1)});
    }

    // Hybrid and frame: range-major, so early frames complete (and leave memory) first.
    for (auto &r : ranges) {
        for (int t = 0; t < tiles(); t++) {
            // Skip cells already done inside this tile (never the case after a whole-frame
            // resume, but keeps the invariant exact).
            int lo = r.first;
            while (lo <= r.second) {
                while (lo <= r.second && done(t, lo))
                    lo++;
                int hi = lo;
                while (hi + 1 <= r.second && !done(t, hi + 1))
                    hi++;
                if (lo <= r.second)
                    add_unit(t, lo, hi, false);
                lo = hi + 1;
            }
        }
    }
}

const Unit *Schedule::find(int id) const
{
    auto it = units_.find(id);
    return it == units_.end() ? nullptr : &it->second;
}

int Schedule::running() const
{
    int n = 0;
    for (auto &kv : units_)
        if (kv.second.live && kv.second.slave != 0)
            n++;
    return n;
}

void Schedule::assign(int id, int tid, double t)
{
    Unit &u = units_.at(id);
    auto it = std::find(queue_.begin(), queue_.end(), id);
    if (it != queue_.end())
        queue_.erase(it);
    u.slave = tid;
    u.started = t;
}

Action Schedule::next_for(int tid, double t, bool allow_duplicates)
{
    Action a;
    // 1. Queued work, skipping cells finished meanwhile.
    while (!queue_.empty()) {
        int id = queue_.front();
        Unit &u = units_.at(id);
        while (u.next <= u.hi && done(u.tile, u.next))
            u.next++;
        while (u.hi >= u.next && done(u.tile, u.hi))
            u.hi--;
        if (u.next > u.hi) {
            queue_.pop_front();
            u.live = false;
            continue;
        }
        u.lo = u.next;
        assign(id, tid, t);
        a.kind = Action::Run;
        a.unit = id;
        return a;
    }

    // 2. Split the running unit with the most work left (frames x tile pixels).
    Unit *best = nullptr;
    long best_work = 0;
    for (auto &kv : units_) {
        Unit &u = kv.second;
        if (!u.live || u.slave == 0 || u.truncating || u.cancelling || u.dup_of >= 0 ||
            u.has_dup || u.no_split)
            continue;
        if (u.remaining() < 2)
            continue;
        long work = long(u.remaining()) * tiles_[size_t(u.tile)].area();
        if (work > best_work) {
            best_work = work;
            best = &u;
        }
    }
    if (best) {
        best->truncating = true;
        best->reserved = tid;
        a.kind = Action::Split;
        a.unit = best->id;
        // The slave keeps the first half, including the frame it is rendering now.
        a.new_hi = best->next + (best->remaining() + 1) / 2 - 1;
        return a;
    }

    // 3. Straggler: duplicate the oldest running unit that still has undone cells.
    if (!allow_duplicates)
        return a;
    Unit *oldest = nullptr;
    for (auto &kv : units_) {
        Unit &u = kv.second;
        if (!u.live || u.slave == 0 || u.slave == tid || u.truncating || u.cancelling ||
            u.dup_of >= 0 || u.has_dup)
            continue;
        if (u.next > u.hi || all_done(u.tile, u.next, u.hi))
            continue;
        if (!oldest || u.started < oldest->started)
            oldest = &u;
    }
    if (oldest) {
        int lo = oldest->next;
        while (done(oldest->tile, lo))
            lo++;
        int id = add_unit(oldest->tile, lo, oldest->hi, true);
        Unit &d = units_.at(id);
        d.dup_of = oldest->id;
        oldest->has_dup = true;
        assign(id, tid, t);
        a.kind = Action::Run;
        a.unit = id;
    }
    return a;
}

bool Schedule::frame_arrived(int id, int index, std::vector<int> &cancel)
{
    auto it = units_.find(id);
    if (it == units_.end() || index < 0 || index >= nframes_)
        return false;
    Unit &u = it->second;
    u.next = std::max(u.next, index + 1);
    bool fresh = !done(u.tile, index);
    if (fresh)
        mark_done(u.tile, index);
    // Any running unit of this tile whose remaining cells are all done has nothing to add.
    for (auto &kv : units_) {
        Unit &v = kv.second;
        if (!v.live || v.slave == 0 || v.tile != u.tile || v.cancelling || v.next > v.hi)
            continue;
        if (all_done(v.tile, v.next, v.hi)) {
            v.cancelling = true;
            cancel.push_back(v.id);
        }
    }
    return fresh;
}

int Schedule::truncated(int id, int accepted, int &reserved)
{
    reserved = 0;
    auto it = units_.find(id);
    if (it == units_.end())
        return -1;
    Unit &u = it->second;
    if (!u.truncating)
        return -1;
    u.truncating = false;
    reserved = u.reserved;
    u.reserved = 0;
    if (!u.live || accepted < 0)
        return -1;
    int old_hi = u.hi;
    u.hi = std::min(old_hi, std::max(accepted, u.next - 1));
    if (u.hi >= old_hi)
        return -1;
    return add_unit(u.tile, u.hi + 1, old_hi, true);
}

int Schedule::truncate_timed_out(int id)
{
    auto it = units_.find(id);
    if (it == units_.end() || !it->second.truncating)
        return 0;
    Unit &u = it->second;
    int reserved = u.reserved;
    u.truncating = false;
    u.reserved = 0;
    u.no_split = true;
    return reserved;
}

bool Schedule::covered(int tile, int index, int except) const
{
    for (auto &kv : units_) {
        const Unit &v = kv.second;
        if (!v.live || v.id == except || v.tile != tile)
            continue;
        int from = v.slave != 0 ? v.next : v.lo;
        if (index >= from && index <= v.hi)
            return true;
    }
    return false;
}

int Schedule::repair()
{
    int added = 0;
    for (int t = 0; t < tiles(); t++) {
        int run_lo = -1;
        for (int i = 0; i <= nframes_; i++) {
            bool missing = i < nframes_ && !done(t, i) && !covered(t, i, -1);
            if (missing && run_lo < 0)
                run_lo = i;
            if (!missing && run_lo >= 0) {
                add_unit(t, run_lo, i - 1, false);
                added++;
                run_lo = -1;
            }
        }
    }
    return added;
}

int Schedule::unit_ended(int id)
{
    auto it = units_.find(id);
    if (it == units_.end() || !it->second.live)
        return 0;
    Unit &u = it->second;
    u.live = false;
    auto q = std::find(queue_.begin(), queue_.end(), id);
    if (q != queue_.end())
        queue_.erase(q);
    int reserved = 0;
    if (u.truncating) {
        reserved = u.reserved;
        u.truncating = false;
        u.reserved = 0;
    }
    // Unlink duplicates so the survivor can be split or duplicated again.
    if (u.dup_of >= 0) {
        auto o = units_.find(u.dup_of);
        if (o != units_.end())
            o->second.has_dup = false;
    }
    if (u.has_dup) {
        for (auto &kv : units_)
            if (kv.second.live && kv.second.dup_of == id)
                kv.second.dup_of = -1;
        u.has_dup = false;
    }
    // Re-queue uncovered missing cells as consecutive runs, oldest work first.
    std::vector<std::pair<int, int>> runs;
    // From lo, not next: a cell the unit skipped (lost output) is re-queued too.
    for (int i = u.lo; i <= u.hi; i++) {
        if (done(u.tile, i) || covered(u.tile, i, id))
            continue;
        if (!runs.empty() && runs.back().second == i - 1)
            runs.back().second = i;
        else
            runs.push_back({i, i});
    }
    for (auto r = runs.rbegin(); r != runs.rend(); ++r)
        add_unit(u.tile, r->first, r->second, true);
    return reserved;
}

} // namespace fc
