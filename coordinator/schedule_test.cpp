// schedule_test.cpp - unit tests of the work-unit bookkeeping (no PVM, no renderer).
// Run: make -C coordinator test-schedule
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <vector>

#include "schedule.h"

using namespace fc;

static int failures = 0;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            failures++;                                                              \
        }                                                                            \
    } while (0)

// Every cell that is not done is covered by a live unit (queued: lo..hi, running: next..hi).
static bool covered_everywhere(const Schedule &s)
{
    for (int t = 0; t < s.tiles(); t++)
        for (int i = 0; i < s.frames(); i++) {
            if (s.done(t, i))
                continue;
            bool cov = false;
            for (auto &kv : s.units()) {
                const Unit &u = kv.second;
                int from = u.slave ? u.next : u.lo;
                cov = cov || (u.live && u.tile == t && i >= from && i <= u.hi);
            }
            if (!cov)
                return false;
        }
    return true;
}

static void test_plan_sequence()
{
    Schedule s({Rect{0, 0, 10, 10}}, 10);
    s.plan(Division::Sequence, 3);
    // Three consecutive ranges of ceil(10/3) frames.
    CHECK(s.queued() == 3);
    std::vector<std::pair<int, int>> ranges;
    for (auto &kv : s.units())
        ranges.push_back({kv.second.lo, kv.second.hi});
    CHECK((ranges == std::vector<std::pair<int, int>>{{0, 3}, {4, 7}, {8, 9}}));
    CHECK(covered_everywhere(s));
}

static void test_plan_frame_and_hybrid()
{
    std::vector<Rect> tiles = make_tiles(Rect{0, 0, 160, 120}, 80);
    CHECK(tiles.size() == 4);
    CHECK((tiles[3] == Rect{80, 80, 160, 120}));
    Schedule f(tiles, 6);
    f.plan(Division::Frame, 2);
    // Frame division: every tile over the whole range.
    CHECK(f.queued() == 4);
    for (auto &kv : f.units())
        CHECK(kv.second.lo == 0 && kv.second.hi == 5);
    Schedule h(tiles, 6);
    h.plan(Division::Hybrid, 2);
    // Hybrid: 2 ranges x 4 tiles, earlier range first.
    CHECK(h.queued() == 8);
    CHECK(h.unit(1).hi == 2 && h.unit(5).lo == 3);
}

static void test_resume_skips_done_frames()
{
    Schedule s({Rect{0, 0, 4, 4}}, 10);
    for (int i : {0, 1, 5})
        s.mark_done(0, i);
    s.plan(Division::Sequence, 1);
    // Units never span a frame that is already done.
    std::vector<std::pair<int, int>> ranges;
    for (auto &kv : s.units())
        ranges.push_back({kv.second.lo, kv.second.hi});
    CHECK((ranges == std::vector<std::pair<int, int>>{{2, 4}, {6, 9}}));
    CHECK(s.frames_done() == 3);
}

static void test_split_and_truncate()
{
    Schedule s({Rect{0, 0, 4, 4}}, 10);
    s.plan(Division::Sequence, 1);
    Action a = s.next_for(100, 0, true);
    CHECK(a.kind == Action::Run);
    int big = a.unit;
    std::vector<int> cancel;
    s.frame_arrived(big, 0, cancel);
    s.frame_arrived(big, 1, cancel);
    // Nothing queued: the idle slave gets half of what is left (next = 2, 8 frames left).
    Action b = s.next_for(200, 1, true);
    CHECK(b.kind == Action::Split && b.unit == big && b.new_hi == 5);
    // The busy slave had already started frame 6: it keeps 2..6, the tail is 7..9.
    int reserved = 0;
    int tail = s.truncated(big, 6, reserved);
    CHECK(reserved == 200 && tail > 0);
    CHECK(s.unit(big).hi == 6);
    CHECK(s.unit(tail).lo == 7 && s.unit(tail).hi == 9);
    s.assign(tail, 200, 1);
    CHECK(covered_everywhere(s));
    // A unit that already finished everything yields no tail.
    Action c = s.next_for(300, 2, false);
    CHECK(c.kind == Action::Split);
    int r2 = 0;
    CHECK(s.truncated(c.unit, s.unit(c.unit).hi, r2) == -1 && r2 == 300);
}

static void test_dead_slave_requeues()
{
    Schedule s({Rect{0, 0, 4, 4}}, 6);
    s.plan(Division::Sequence, 1);
    Action a = s.next_for(100, 0, true);
    std::vector<int> cancel;
    s.frame_arrived(a.unit, 0, cancel);
    s.unit_ended(a.unit);
    // The dead slave's remaining frames are queued again, nothing more.
    CHECK(s.queued() == 1);
    Action b = s.next_for(200, 1, true);
    CHECK(b.kind == Action::Run && s.unit(b.unit).lo == 1 && s.unit(b.unit).hi == 5);
    CHECK(covered_everywhere(s));
}

static void test_skipped_cell_requeued()
{
    Schedule s({Rect{0, 0, 4, 4}}, 5);
    s.plan(Division::Sequence, 1);
    Action a = s.next_for(100, 0, true);
    std::vector<int> cancel;
    for (int i : {0, 1, 3, 4})
        s.frame_arrived(a.unit, i, cancel);
    s.unit_ended(a.unit);
    // A cell the unit never delivered (lost renderer output) is queued again.
    CHECK(s.queued() == 1);
    Action b = s.next_for(100, 1, true);
    CHECK(b.kind == Action::Run && s.unit(b.unit).lo == 2 && s.unit(b.unit).hi == 2);
}

static void test_repair()
{
    Schedule s({Rect{0, 0, 4, 4}, Rect{4, 0, 8, 4}}, 4);
    s.plan(Division::Frame, 1);
    CHECK(s.repair() == 0);     // the plan covers everything
    s.mark_done(0, 0);
    std::vector<int> ids;
    for (auto &kv : s.units())
        ids.push_back(kv.first);
    for (int id : ids) {
        s.unit(id).live = false;    // simulate lost bookkeeping
    }
    // Every missing cell is covered again: tile 0 frames 1..3, tile 1 frames 0..3.
    CHECK(s.repair() == 2);
    CHECK(covered_everywhere(s));
}

static void test_straggler_duplicate()
{
    Schedule s({Rect{0, 0, 4, 4}}, 1);
    s.plan(Division::Sequence, 1);
    Action a = s.next_for(100, 0, true);
    // One frame left, cannot split: the idle slave duplicates it.
    Action b = s.next_for(200, 1, true);
    CHECK(b.kind == Action::Run && b.unit != a.unit && s.unit(b.unit).dup_of == a.unit);
    CHECK(s.next_for(300, 2, true).kind == Action::None);   // one copy only
    std::vector<int> cancel;
    // First result wins; the other copy has nothing left and is cancelled.
    CHECK(s.frame_arrived(b.unit, 0, cancel));
    CHECK(cancel == std::vector<int>{a.unit});
    CHECK(!s.frame_arrived(a.unit, 0, cancel));
    CHECK(s.finished());
    CHECK(s.next_for(300, 3, false).kind == Action::None);
}

// Random slaves finish frames, get split, die; the work always completes and, without
// duplicates, no cell is ever rendered twice.
static void test_simulation(Division div, unsigned seed)
{
    std::mt19937 rng(seed);
    std::vector<Rect> tiles = div == Division::Sequence ? std::vector<Rect>{Rect{0, 0, 160, 120}}
                                                        : make_tiles(Rect{0, 0, 160, 120}, 80);
    Schedule s(tiles, 17);
    s.plan(div, 3);
    std::map<int, int> running;     // slave -> unit
    std::map<int, int> waiting;     // reserved slave -> unit being truncated
    std::vector<int> idle = {1, 2, 3, 4};
    int next_slave = 5, renders = 0, steps = 0;
    std::map<std::pair<int, int>, int> rendered;
    while (!s.finished() && steps++ < 10000) {
        for (size_t k = 0; k < idle.size();) {
            int tid = idle[k];
            Action a = s.next_for(tid, steps, false);
            if (a.kind == Action::Run) {
                running[tid] = a.unit;
                idle.erase(idle.begin() + long(k));
            } else if (a.kind == Action::Split) {
                waiting[tid] = a.unit;
                // The busy slave answers at once, possibly past the requested frame.
                int accepted = a.new_hi + int(rng() % 2);
                accepted = std::min(accepted, s.unit(a.unit).hi);
                int reserved = 0;
                int tail = s.truncated(a.unit, accepted, reserved);
                CHECK(reserved == tid);
                waiting.erase(tid);
                idle.erase(idle.begin() + long(k));
                if (tail >= 0) {
                    s.assign(tail, tid, steps);
                    running[tid] = tail;
                } else {
                    idle.push_back(tid);
                    break;
                }
            } else {
                k++;
            }
        }
        CHECK(covered_everywhere(s));
        if (running.empty())
            break;
        auto it = running.begin();
        std::advance(it, long(rng() % running.size()));
        int tid = it->first, id = it->second;
        if (rng() % 23 == 0) {
            // The slave dies: its unit ends unfinished, a new slave joins.
            s.unit_ended(id);
            running.erase(it);
            idle.push_back(next_slave++);
            continue;
        }
        Unit &u = s.unit(id);
        std::vector<int> cancel;
        rendered[{u.tile, u.next}]++;
        renders++;
        s.frame_arrived(id, u.next, cancel);
        if (u.next > u.hi) {
            s.unit_ended(id);
            running.erase(it);
            idle.push_back(tid);
        }
    }
    CHECK(s.finished());
    for (auto &kv : rendered)
        CHECK(kv.second == 1);
}

int main()
{
    test_plan_sequence();
    test_plan_frame_and_hybrid();
    test_resume_skips_done_frames();
    test_split_and_truncate();
    test_dead_slave_requeues();
    test_straggler_duplicate();
    test_skipped_cell_requeued();
    test_repair();
    for (unsigned seed = 1; seed <= 50; seed++) {
        test_simulation(Division::Sequence, seed);
        test_simulation(Division::Frame, seed);
        test_simulation(Division::Hybrid, seed);
    }
    if (failures) {
        fprintf(stderr, "schedule_test: %d check(s) failed\n", failures);
        return 1;
    }
    printf("schedule_test: all checks passed\n");
    return 0;
}
