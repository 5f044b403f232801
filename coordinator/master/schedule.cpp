// schedule.cpp - per-frame jobs out of frame ranges: divide, balance, split, duplicate, retry.
#include "schedule.h"

#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>

namespace fc {

namespace {

// With fc, move tiles while a slave's share exceeds its speed's by this much: a move costs its
// new slave a full trace of the tile.
const double kImbalance = 1.2;

} // namespace

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

Schedule::Schedule(const std::vector<Rect> &tiles, const CellGrid &cells, const CostModel &costs,
                   Division division)
    : tiles_(tiles), cells_(cells), costs_(costs), division_(division)
{
}

std::vector<int> Schedule::missing(int index, const std::vector<int> &tiles) const
{
    std::vector<int> m;
    for (int t : tiles)
        if (!done(index, t))
            m.push_back(t);
    return m;
}

void Schedule::plan(int parts, int slaves)
{
    std::vector<int> todo;
    for (int i = 0; i < frames(); i++)
        if (!frame_done(i))
            todo.push_back(i);
    if (todo.empty())
        return;
    parts = division_ == Division::Frame ? 1 : std::max(1, std::min(parts, int(todo.size())));
    hybrid_members_ = std::max(1, (slaves + parts - 1) / parts);
    // Ranges of about equally many missing frames; a range may span finished frames (the
    // renderer skips them without parsing).
    for (int p = 0; p < parts; p++) {
        size_t a = todo.size() * size_t(p) / size_t(parts);
        size_t b = todo.size() * size_t(p + 1) / size_t(parts);
        if (a == b)
            continue;
        Range r;
        r.lo = r.frontier = todo[a];
        r.hi = todo[b - 1];
        ranges_.push_back(r);
    }
}

void Schedule::add_slave(int slave, int host)
{
    SlaveState &s = slaves_[slave];
    s.host = host;
}

int Schedule::add_job(int slave, int index, const std::vector<int> &tiles, int range, double t)
{
    Job j;
    j.id = next_id_++;
    j.index = index;
    j.tiles = tiles;
    std::sort(j.tiles.begin(), j.tiles.end());
    j.slave = slave;
    j.range = range;
    j.started = t;
    auto known = slaves_.find(slave);
    if (known != slaves_.end())
        known->second.last = std::max(known->second.last, index);
    // A slave renders its jobs in the order it got them: the first is being rendered now.
    if (live_jobs(slave) == 0)
        j.rendering = t;
    jobs_[j.id] = j;
    return j.id;
}

void Schedule::orphan(int index, const std::vector<int> &tiles, int failures, int avoid_host)
{
    std::vector<int> m = missing(index, tiles);
    if (m.empty())
        return;
    Orphan o;
    o.index = index;
    o.tiles = m;
    o.failures = failures;
    if (avoid_host != 0)
        o.avoid_hosts.insert(avoid_host);
    // Oldest frame first: it holds up the frames after it.
    auto pos = std::find_if(orphans_.begin(), orphans_.end(),
                            [&](const Orphan &x) { return x.index > index; });
    orphans_.insert(pos, o);
}

void Schedule::leave_range(int slave)
{
    SlaveState &s = slaves_[slave];
    if (s.range < 0)
        return;
    Range &r = ranges_[size_t(s.range)];
    r.members.erase(std::remove(r.members.begin(), r.members.end(), slave), r.members.end());
    // Tiles set aside for it in frames it has not taken yet go to whoever comes next.
    for (auto &kv : r.reserved) {
        auto it = kv.second.find(slave);
        if (it != kv.second.end()) {
            orphan(kv.first, it->second, 0, 0);
            kv.second.erase(it);
        }
    }
    for (auto &kv : r.owner)
        if (kv.second == slave)
            kv.second = 0;
    s.range = -1;
}

std::vector<int> Schedule::remove_slave(int slave)
{
    std::vector<int> lost;
    auto it = slaves_.find(slave);
    if (it == slaves_.end())
        return lost;
    leave_range(slave);
    for (auto &kv : jobs_) {
        Job &j = kv.second;
        if (!j.live || j.slave != slave)
            continue;
        j.live = false;
        lost.push_back(j.id);
        if (Job *o = j.dup_of >= 0 && jobs_.count(j.dup_of) ? &jobs_[j.dup_of] : nullptr)
            o->has_dup = false;
        // A duplicate still running covers these cells; otherwise they are orphans.
        bool covered = false;
        for (auto &kv2 : jobs_) {
            const Job &d = kv2.second;
            if (d.live && d.index == j.index && (d.dup_of == j.id || j.dup_of == d.id))
                covered = true;
        }
        if (!covered)
            orphan(j.index, j.tiles, j.failures, 0);
    }
    slaves_.erase(it);
    prune();
    return lost;
}

int Schedule::oldest_unfinished(Range &range) const
{
    // Frames only ever get done, so the scan resumes where it stopped: O(1) amortized.
    range.oldest = std::max(range.oldest, range.lo);
    while (range.oldest <= range.hi && frame_done(range.oldest))
        range.oldest++;
    return range.oldest;
}

// Speeds of r's members; a slave not measured yet counts as fast as the average measured one.
std::map<int, double> Schedule::member_speeds(const Range &r) const
{
    double measured = 0;
    int nmeasured = 0;
    for (int s : r.members) {
        double v = costs_.speed(s);
        if (v > 0) {
            measured += v;
            nmeasured++;
        }
    }
    double typical = nmeasured > 0 ? measured / nmeasured : 1.0;
    std::map<int, double> speed;
    for (int s : r.members) {
        double v = costs_.speed(s);
        speed[s] = v > 0 ? v : typical;
    }
    return speed;
}

int Schedule::window(const Range &range) const
{
    // A frame that goes whole reaches the master complete (it holds none of them), but every
    // member has up to two queued: the window must not stop a fast member while the slowest
    // renders its two. Divided frames (the last ones) stay within kWindow: the master holds
    // them until their last tile.
    if (costs_.cheap_moves() && range.members.size() > 1 && range.frontier <= range.hi &&
        whole_frames(range, range.frontier, member_speeds(range)))
        return kWindow + 2 * int(range.members.size());
    return kWindow;
}

long Schedule::range_work(const Range &range) const
{
    if (range.frontier > range.hi)
        return 0;
    long area = 0;
    for (const Rect &t : tiles_)
        area += t.area();
    return long(range.hi - range.frontier + 1) * area;
}

// Divide frame `index` of range r among its members at time `when`. With fc each keeps the
// tiles it had, new tiles go to the least loaded, and tiles move from the most to the least
// loaded member (by speed) only while the imbalance exceeds kImbalance. Without fc the frame
// goes whole to the member that would finish it first while enough frames follow it to keep
// the others busy (whole_frames), and the last few are dealt afresh in shares that let the
// members finish together (finish_together).
void Schedule::divide(int ri, int index, double when)
{
    Range &r = ranges_[size_t(ri)];
    const std::vector<int> &m = r.members;
    if (m.empty())
        return;
    std::vector<int> todo;
    for (int t = 0; t < tiles(); t++)
        if (!done(index, t))
            todo.push_back(t);
    if (todo.empty())
        return;
    const std::map<int, double> speed = member_speeds(r);
    double total_speed = 0;
    for (auto &kv : speed)
        total_speed += kv.second;
    double area = 0;
    for (int t : todo)
        area += tiles_[size_t(t)].area();
    if (costs_.cheap_moves() && whole_frames(r, index, speed)) {
        const std::map<int, double> free_at = seconds_until_free(r, index, when, speed);
        int first = m[0];
        for (int s : m)
            if (free_at.at(s) + area / speed.at(s) < free_at.at(first) + area / speed.at(first))
                first = s;
        r.reserved[index][first] = todo;
        r.lagging = false;
        return;
    }
    std::map<int, double> load, target;
    std::map<int, std::vector<int>> share;
    for (int s : m) {
        load[s] = 0;
        target[s] = area * speed.at(s) / total_speed;
    }
    if (costs_.cheap_moves())
        finish_together(r, index, when, area, speed, target);
    bool first_division = true;
    for (int t : todo) {
        auto o = r.owner.find(t);
        if (o != r.owner.end() && load.count(o->second))
            first_division = false;
    }
    // Tile t to the member furthest below its share (by speed).
    auto deal = [&](int t) {
        int best = m[0];
        for (int s : m)
            if (load[s] / target[s] < load[best] / target[best])
                best = s;
        share[best].push_back(t);
        load[best] += tiles_[size_t(t)].area();
    };
    if (first_division || costs_.cheap_moves()) {
        // Tiles dealt in raster order to the member furthest below its share (by speed):
        // every slave gets tiles all over the frame, so a region that is expensive to render
        // (frame coherence re-traces only what moved) is shared instead of holding one back.
        // Without fc every frame is dealt afresh: no renderer keeps state in its tiles, and
        // tiles spread over the frame keep a slave's measured pixels per second free of
        // where its tiles lie (moving the tiles nearest a slave's own, as with fc, can give
        // a slave a cluster of cheap or dear tiles and skew its speed).
        for (int t : todo)
            deal(t);
    } else {
        std::vector<int> unowned;
        for (int t : todo) {
            auto o = r.owner.find(t);
            if (o != r.owner.end() && load.count(o->second)) {
                share[o->second].push_back(t);
                load[o->second] += tiles_[size_t(t)].area();
            } else {
                unowned.push_back(t);
            }
        }
        for (int t : unowned)
            deal(t);
        // Move tiles from the most to the least loaded member while it pays.
        bool moved = false;
        bool may_move = r.lagging && index - r.last_move >= kMoveGap;
        for (int moves = 0; may_move && moves < tiles(); moves++) {
            int over = m[0], under = m[0];
            for (int s : m) {
                if (load[s] / target[s] > load[over] / target[over]) over = s;
                if (load[s] / target[s] < load[under] / target[under]) under = s;
            }
            if (over == under || share[over].size() <= 1 || load[over] / target[over] <= kImbalance)
                break;
            // The tile of `over` nearest to `under`'s tiles (raster distance) keeps shares compact.
            int pick = -1;
            long best_d = LONG_MAX;
            for (int t : share[over]) {
                long d = LONG_MAX;
                for (int u : share[under])
                    d = std::min(d, long(std::abs(u - t)));
                if (share[under].empty())
                    d = 0;
                if (d < best_d) {
                    best_d = d;
                    pick = t;
                }
            }
            double a = tiles_[size_t(pick)].area();
            // Stop when moving would only swap the roles of the two.
            if ((load[under] + a) / target[under] >= load[over] / target[over])
                break;
            share[over].erase(std::find(share[over].begin(), share[over].end(), pick));
            share[under].push_back(pick);
            load[over] -= a;
            load[under] += a;
            moved = true;
        }
        if (moved)
            r.last_move = index;
    }
    r.lagging = false;
    for (auto &kv : share) {
        if (kv.second.empty())
            continue;
        std::sort(kv.second.begin(), kv.second.end());
        r.reserved[index][kv.first] = kv.second;
        for (int t : kv.second)
            r.owner[t] = kv.first;
    }
}

// Without fc a job's fixed costs (its renderer parses the frame and sets it up, its result
// is a message of its own) are paid once per member that holds tiles of a frame: at 320x240
// Newton's parse alone is a tenth of a frame, and three slaves dividing every frame took
// 1.27x the CPU of whole frames. Whole frames leave the members'
// finish times up to one frame of the slowest apart, which dividing the last frames evens
// out: as many as the members render in the time the slowest renders one, and at least one
// per member.
bool Schedule::whole_frames(const Range &r, int index, const std::map<int, double> &speed) const
{
    double total = 0, slowest = 0;
    for (auto &kv : speed) {
        total += kv.second;
        slowest = slowest > 0 ? std::min(slowest, kv.second) : kv.second;
    }
    const double tail = std::max(double(speed.size()), std::ceil(total / slowest));
    return double(r.hi - index) >= tail;
}

// Seconds until each member of r is free for frame `index`: its live jobs (less what it
// rendered of the one it renders now) and its reserved shares of earlier frames, at its speed.
std::map<int, double> Schedule::seconds_until_free(const Range &r, int index, double when,
                                                   const std::map<int, double> &speed) const
{
    auto pixels_missing = [&](int frame, const std::vector<int> &tiles) {
        double pixels = 0;
        for (int tile : missing(frame, tiles))
            pixels += tiles_[size_t(tile)].area();
        return pixels;
    };
    std::map<int, double> work;     // pixels each member still has to render before `index`
    for (int s : r.members)
        work[s] = 0;
    for (auto &kv : jobs_) {
        const Job &j = kv.second;
        auto w = work.find(j.slave);
        if (!j.live || w == work.end())
            continue;
        double pixels = pixels_missing(j.index, j.tiles);
        if (j.rendering >= 0)
            pixels = std::max(0.0, pixels - speed.at(j.slave) * (when - j.rendering));
        w->second += pixels;
    }
    for (auto &frame : r.reserved) {
        if (frame.first >= index)
            continue;
        for (auto &share : frame.second) {
            auto w = work.find(share.first);
            if (w != work.end())
                w->second += pixels_missing(frame.first, share.second);
        }
    }
    std::map<int, double> free_at;
    for (auto &w : work)
        free_at[w.first] = w.second / speed.at(w.first);
    return free_at;
}

// Without fc, shares that let every member finish frame `index` at the same time: a member
// still busy with earlier work (its live jobs, its reserved shares of earlier frames) starts
// later and gets less, one that ran ahead gets more. Shares by speed alone keep a lead for
// good: at 1280x960 the full-core host of newton-table finished its last frame 3.8 s before
// the half-core ones, which were two frames behind since the first frames (divided before
// any speed was measured). A member free only after the others finish gets a small share
// rather than none, so that every slave keeps a measured speed.
void Schedule::finish_together(const Range &r, int index, double when, double area,
                               const std::map<int, double> &speed,
                               std::map<int, double> &target) const
{
    std::vector<std::pair<double, int>> free_at;    // seconds until the member is free
    for (auto &kv : seconds_until_free(r, index, when, speed))
        free_at.push_back({kv.second, kv.first});
    std::sort(free_at.begin(), free_at.end());
    // Water filling: the finish time T at which the members free before it, each rendering
    // at its speed from when it is free, cover the frame's area.
    double rate = 0, covered = 0, finish = 0;
    size_t n = 0;
    while (n < free_at.size()) {
        double start = free_at[n].first;
        if (rate > 0 && covered + rate * (start - finish) >= area)
            break;
        covered += rate * (start - finish);
        finish = start;
        rate += speed.at(free_at[n].second);
        n++;
    }
    finish += (area - covered) / rate;
    const double floor = 0.05 * area / double(r.members.size());
    for (auto &fs : free_at)
        target[fs.second] = std::max(floor, speed.at(fs.second) * (finish - fs.first));
}

const Job *Schedule::take_orphan(int slave, double t)
{
    int host = slaves_[slave].host;
    bool other_host = false;
    for (auto &kv : slaves_)
        other_host = other_host || kv.second.host != host;
    for (auto it = orphans_.begin(); it != orphans_.end(); ++it) {
        std::vector<int> m = missing(it->index, it->tiles);
        if (m.empty()) {
            it = orphans_.erase(it);
            if (it == orphans_.end())
                break;
            --it;
            continue;
        }
        // A failed piece of work goes to another host when there is one.
        if (other_host && it->avoid_hosts.count(host))
            continue;
        int id = add_job(slave, it->index, m, -1, t);
        jobs_[id].failures = it->failures;
        orphans_.erase(it);
        return &jobs_[id];
    }
    return nullptr;
}

const Job *Schedule::take_from_range(int slave, double t)
{
    SlaveState &s = slaves_[slave];
    while (s.range >= 0) {
        Range &r = ranges_[size_t(s.range)];
        if (s.cursor > r.hi) {
            leave_range(slave);
            return nullptr;
        }
        if (s.cursor >= r.frontier) {
            if (r.frontier - oldest_unfinished(r) >= window(r)) {
                r.lagging = r.members.size() > 1;
                return nullptr;     // far enough ahead: wait for the others
            }
            divide(s.range, r.frontier, t);
            r.frontier++;
            continue;
        }
        int index = s.cursor++;
        auto res = r.reserved.find(index);
        if (res == r.reserved.end())
            continue;
        auto mine = res->second.find(slave);
        if (mine == res->second.end())
            continue;
        std::vector<int> m = missing(index, mine->second);
        res->second.erase(mine);
        if (res->second.empty())
            r.reserved.erase(res);
        if (m.empty())
            continue;
        int id = add_job(slave, index, m, s.range, t);
        return &jobs_[id];
    }
    return nullptr;
}

// In sequence division a slave that was given frames before renders them first: its renderer
// reaches r's frames with samples (a renderer only goes forward).
bool Schedule::jumps_forward(const Range &r, const SlaveState &s) const
{
    return division_ == Division::Sequence && s.last >= 0 && r.lo > s.last;
}

// A renderer that jumps forward keeps its samples: its first frame there costs at least a
// coherent frame (nothing changed in between) and at most a fresh one (everything did). Until a
// jump was measured it is priced halfway. Priced as fresh, a run's one jump (the fast slave's,
// at the end) took too little: on Newton it costs 2.4 coherent frames against 5 for a fresh
// start, and the fast host sat idle while the others rendered the frames it had left them.
double Schedule::unmeasured_jump_cost() const
{
    return (1 + costs_.fresh_cost()) / 2;
}

int Schedule::split_take(const Range &r, int slave) const
{
    const SlaveState &s = slaves_.at(slave);
    int left = r.hi - r.frontier + 1;
    if (left < 2 || r.members.empty())
        return 0;
    // The newcomer takes n of the left frames: its first one costs `first` frames (fresh, or
    // less for a renderer that jumps forward with its samples). At speeds u (newcomer) and v
    // (the range's slave), in frames a second, both finish together when (first + n - 1) / u
    // = (left - n) / v; taking none is better when n < 1. Speeds not measured yet count as
    // equal.
    double u = 1, v = 1;
    double mine = costs_.speed(slave), theirs = costs_.speed(r.members.front());
    if (mine > 0 && theirs > 0)
        u = mine, v = theirs;
    const double fresh = costs_.fresh_cost(), jump = costs_.jump_cost();
    double first = fresh;
    if (jumps_forward(r, s))
        first = jump > 0 ? std::min(jump, fresh) : unmeasured_jump_cost();
    double balanced = (double(left) * u - (first - 1) * v) / (u + v);
    // Without fc a tie goes to the newcomer (half of an odd number rounds up).
    return std::max(0, int(std::floor(balanced + (fresh > 1 ? 0.0 : 0.5))));
}

// Give a slave without a range one: an abandoned range first, then (frame division) the
// range with the most work per member to join, else the tail of a range split (split_take).
bool Schedule::find_range(int slave)
{
    SlaveState &s = slaves_[slave];
    int best = -1;
    double best_work = 0;
    for (size_t i = 0; i < ranges_.size(); i++) {
        const Range &r = ranges_[i];
        long work = range_work(r);
        if (work <= 0)
            continue;
        double per = r.members.empty() ? 1e300 : double(work) / double(r.members.size());
        if (per > best_work) {
            best_work = per;
            best = int(i);
        }
    }
    if (best < 0)
        return false;
    // Frame division shares a range among as many slaves as it has tiles, hybrid among its
    // share of the slaves; more split it.
    int members = division_ == Division::Frame    ? tiles()
                  : division_ == Division::Hybrid ? std::min(hybrid_members_, tiles())
                                                  : 1;
    Range &r = ranges_[size_t(best)];
    if (r.members.empty() || int(r.members.size()) < members) {
        // A newcomer to a range whose tiles have owners gets its share by rebalancing, at
        // the next division.
        if (!r.owner.empty()) {
            r.lagging = true;
            r.last_move = -1000;
        }
        r.members.push_back(slave);
        s.range = best;
        s.cursor = r.frontier;
        return true;
    }
    // Split the range that gives the newcomer the most frames. With fc in sequence division a
    // renderer that jumps forward keeps its samples (and a renderer cannot go back): the
    // nearest range ahead of the slave's last frame that gives it any goes first, so that its
    // later jumps stay forward too.
    int take = 0;
    bool ahead = false;
    for (size_t i = 0; i < ranges_.size(); i++) {
        const Range &c = ranges_[i];
        if (range_work(c) <= 0 || int(c.members.size()) < members)
            continue;
        int n = split_take(c, slave);
        if (n < 1)
            continue;
        bool forward = costs_.fresh_cost() > 1 && jumps_forward(c, s);
        bool better = forward ? !ahead || c.lo < ranges_[size_t(best)].lo
                              : !ahead && (n > take || (n == take && int(i) == best));
        if (better) {
            take = n;
            best = int(i);
            ahead = forward;
        }
    }
    if (take < 1)
        return false;
    Range tail;
    tail.hi = ranges_[size_t(best)].hi;
    tail.lo = tail.frontier = tail.hi - take + 1;
    ranges_[size_t(best)].hi = tail.lo - 1;
    tail.members.push_back(slave);
    ranges_.push_back(tail);
    s.range = int(ranges_.size()) - 1;
    s.cursor = tail.lo;
    return true;
}

bool Schedule::suspended(int slave) const
{
    auto it = slaves_.find(slave);
    return it != slaves_.end() && it->second.suspended;
}

std::set<int> Schedule::suspended_slaves() const
{
    std::set<int> out;
    for (auto &kv : slaves_)
        if (kv.second.suspended)
            out.insert(kv.first);
    return out;
}

bool Schedule::resume(int slave)
{
    auto it = slaves_.find(slave);
    if (it == slaves_.end() || !it->second.suspended)
        return false;
    for (auto &kv : jobs_)
        if (kv.second.live && kv.second.stalled && kv.second.slave == slave)
            return false;
    it->second.suspended = false;
    return true;
}

void Schedule::stall(int id, std::vector<Job> &cancel)
{
    auto it = jobs_.find(id);
    if (it == jobs_.end() || !it->second.live || it->second.stalled)
        return;
    Job &j = it->second;
    j.stalled = true;
    int slave = j.slave;
    slaves_[slave].suspended = true;
    leave_range(slave);
    for (auto &kv : jobs_) {
        Job &q = kv.second;
        if (!q.live || q.slave != slave || q.id == id)
            continue;
        q.live = false;
        if (q.dup_of >= 0 && jobs_.count(q.dup_of))
            jobs_[q.dup_of].has_dup = false;
        orphan(q.index, q.tiles, q.failures, 0);
        cancel.push_back(q);
    }
    prune();
}

const Job *Schedule::take_stalled(int slave, double t)
{
    int host = slaves_[slave].host;
    for (auto &kv : jobs_) {
        Job &j = kv.second;
        if (!j.live || !j.stalled || j.has_dup || j.slave == slave)
            continue;
        // The stall may be its host's (stopped, unreachable): a slave of another host takes
        // the copy when there is one.
        auto owner = slaves_.find(j.slave);
        int stalled_host = owner == slaves_.end() ? 0 : owner->second.host;
        if (host == stalled_host) {
            bool other_host = false;
            for (auto &s : slaves_)
                other_host = other_host || (s.second.host != stalled_host && !suspended(s.first));
            if (other_host)
                continue;
        }
        std::vector<int> m = missing(j.index, j.tiles);
        if (m.empty())
            continue;
        int oid = j.id;
        int id = add_job(slave, j.index, m, -1, t);
        jobs_[id].dup_of = oid;
        jobs_[id].failures = jobs_[oid].failures;
        jobs_[oid].has_dup = true;
        return &jobs_[id];
    }
    return nullptr;
}

void Schedule::frame_settled(int index, std::vector<Job> &cancel, double t)
{
    for (auto &kv : jobs_) {
        Job &o = kv.second;
        if (o.live && o.index == index && missing(o.index, o.tiles).empty()) {
            o.live = false;
            cancel.push_back(o);
        }
    }
    for (const Job &c : cancel)
        next_rendering(c.slave, t);
    prune();
}

const Job *Schedule::duplicate(int slave, double t)
{
    // Only a job a slave is rendering (its oldest) counts, and only once it has taken clearly
    // longer than jobs usually take: a copy costs its new slave a restart.
    Job *oldest = nullptr;
    for (auto &kv : jobs_) {
        Job &j = kv.second;
        if (!j.live || j.stalled || j.slave == slave || j.rendering < 0 || j.dup_of >= 0 ||
            j.has_dup || missing(j.index, j.tiles).empty())
            continue;
        if (t - j.rendering < std::max(kStragglerSeconds, 2 * costs_.job_seconds()))
            continue;
        if (!oldest || j.rendering < oldest->rendering)
            oldest = &j;
    }
    if (!oldest)
        return nullptr;
    int oid = oldest->id;
    int id = add_job(slave, oldest->index, missing(oldest->index, oldest->tiles), -1, t);
    jobs_[id].dup_of = oid;
    jobs_[oid].has_dup = true;
    return &jobs_[id];
}

const Job *Schedule::next_job(int slave, double t, bool allow_duplicates)
{
    if (!slaves_.count(slave) || finished())
        return nullptr;
    if (suspended(slave))
        return nullptr;
    // Every slave belongs to a range before any frame is divided, so a division counts all.
    for (auto &kv : slaves_)
        if (kv.second.range < 0 && !suspended(kv.first))
            find_range(kv.first);
    if (const Job *j = take_orphan(slave, t))
        return j;
    if (const Job *j = take_stalled(slave, t))
        return j;
    for (int attempt = 0; attempt < 3; attempt++) {
        if (slaves_[slave].range < 0 && !find_range(slave))
            break;
        if (const Job *j = take_from_range(slave, t))
            return j;
        if (slaves_[slave].range >= 0)
            return nullptr;     // waiting for the others in its range
    }
    if (!allow_duplicates)
        return nullptr;
    // Duplicate only at the end, when no range has frames left to divide.
    for (const Range &r : ranges_)
        if (range_work(r) > 0)
            return nullptr;
    if (!orphans_.empty())
        return nullptr;
    return duplicate(slave, t);
}

// The slave's oldest live job is the one it renders now.
void Schedule::next_rendering(int slave, double t)
{
    Job *first = nullptr;
    for (auto &kv : jobs_)
        if (kv.second.live && kv.second.slave == slave && (!first || kv.first < first->id))
            first = &kv.second;
    if (first && first->rendering < 0)
        first->rendering = t;
}

void Schedule::job_done(int id, int index, std::vector<Job> &cancel, double t)
{
    if (index < 0 || index >= frames())
        return;
    auto it = jobs_.find(id);
    int slave = 0;
    if (it != jobs_.end()) {
        it->second.live = false;
        slave = it->second.slave;
        if (it->second.dup_of >= 0 && jobs_.count(it->second.dup_of))
            jobs_[it->second.dup_of].has_dup = false;
    }
    // Copies of the same cells have nothing left to add.
    for (auto &kv : jobs_) {
        Job &o = kv.second;
        if (!o.live || o.index != index || o.id == id)
            continue;
        if (missing(o.index, o.tiles).empty()) {
            o.live = false;
            cancel.push_back(o);
        }
    }
    if (slave != 0)
        next_rendering(slave, t);
    for (const Job &c : cancel)
        next_rendering(c.slave, t);
    prune();
}

// Finished jobs are forgotten: the schedule's memory does not grow with the frames.
void Schedule::prune()
{
    for (auto k = jobs_.begin(); k != jobs_.end();)
        k = k->second.live ? std::next(k) : jobs_.erase(k);
}

int Schedule::job_failed(int id, double t)
{
    auto it = jobs_.find(id);
    if (it == jobs_.end() || !it->second.live)
        return 0;
    Job j = it->second;
    jobs_.erase(it);
    if (j.dup_of >= 0 && jobs_.count(j.dup_of))
        jobs_[j.dup_of].has_dup = false;
    auto s = slaves_.find(j.slave);
    orphan(j.index, j.tiles, j.failures + 1, s == slaves_.end() ? 0 : s->second.host);
    next_rendering(j.slave, t);
    return missing(j.index, j.tiles).empty() ? 0 : j.failures + 1;
}

const Job *Schedule::find(int id) const
{
    auto it = jobs_.find(id);
    return it == jobs_.end() ? nullptr : &it->second;
}

int Schedule::live_jobs(int slave) const
{
    int n = 0;
    for (auto &kv : jobs_)
        n += kv.second.live && kv.second.slave == slave;
    return n;
}

int Schedule::repair()
{
    // Cells a live job, an orphan, or a range's reservation or undivided frames will render.
    std::vector<char> covered(size_t(frames()) * tiles_.size(), 0);
    auto cover = [&](int index, const std::vector<int> &tiles) {
        for (int t : tiles)
            covered[size_t(index) * tiles_.size() + size_t(t)] = 1;
    };
    for (auto &kv : jobs_)
        if (kv.second.live)
            cover(kv.second.index, kv.second.tiles);
    for (const Orphan &o : orphans_)
        cover(o.index, o.tiles);
    for (const Range &r : ranges_) {
        for (auto &kv : r.reserved)
            for (auto &share : kv.second)
                cover(kv.first, share.second);
        for (int i = r.frontier; i <= r.hi; i++)
            for (int t = 0; t < tiles(); t++)
                covered[size_t(i) * tiles_.size() + size_t(t)] = 1;
    }
    int added = 0;
    for (int i = 0; i < frames(); i++) {
        std::vector<int> lost;
        for (int t = 0; t < tiles(); t++)
            if (!done(i, t) && !covered[size_t(i) * tiles_.size() + size_t(t)])
                lost.push_back(t);
        if (!lost.empty()) {
            orphan(i, lost, 0, 0);
            added += int(lost.size());
        }
    }
    return added;
}

} // namespace fc
