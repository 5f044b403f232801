// schedule_test.cpp - unit tests of the job bookkeeping (no PVM, no renderer).
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "schedule.h"

using namespace fc;

static const Rect kArea{0, 0, 160, 120};

// A schedule with the frames' cells and the costs it reads, as fc-master holds them: the cells
// are marked as the frame book marks them, the costs set as the results would set them.
struct Board : CellGrid, CostModel, Schedule {
    Board(const std::vector<Rect> &tiles, int frames, Division division)
        : CellGrid(frames, int(tiles.size())), Schedule(tiles, *this, *this, division)
    {
    }
    using CellGrid::done;
    using CellGrid::frame_done;
    using Schedule::frames;
    using Schedule::tiles;
};

// The result of job j arrives, every tile of it: its new cells are marked, then the schedule
// learns of it. Returns the tiles that were new.
static std::vector<int> job_done(Board &s, int id, int index, const std::vector<int> &tiles,
                                 std::vector<Job> &cancel, double t)
{
    std::vector<int> fresh;
    for (int tile : tiles)
        if (s.mark(index, tile))
            fresh.push_back(tile);
    s.job_done(id, index, cancel, t);
    return fresh;
}

// Deliver job j: every tile of it arrives.
static std::vector<int> deliver(Board &s, const Job &j, std::vector<Job> *cancelled = nullptr,
                                double t = 0)
{
    std::vector<Job> cancel;
    Job copy = j;
    std::vector<int> fresh = job_done(s, copy.id, copy.index, copy.tiles, cancel, t);
    if (cancelled)
        *cancelled = cancel;
    return fresh;
}

// Frames some but not all of whose tiles are done: what the master holds in memory.
static int partial_frames(const Board &s)
{
    int partial = 0;
    for (int i = 0; i < s.frames(); i++) {
        bool some = false;
        for (int t = 0; t < s.tiles(); t++)
            some = some || s.done(i, t);
        partial += some && !s.frame_done(i);
    }
    return partial;
}

TEST(Schedule, SequenceRanges)
{
    Board s({kArea}, 10, Division::Sequence);
    for (int slave : {1, 2, 3})
        s.add_slave(slave, 100);
    s.plan(3);
    // Each slave starts its own consecutive range: 0..2, 3..5, 6..9.
    EXPECT_TRUE(s.next_job(1, 0, true)->index == 0);
    EXPECT_TRUE(s.next_job(2, 0, true)->index == 3);
    EXPECT_TRUE(s.next_job(3, 0, true)->index == 6);
    // A slave's next job is the next frame of its range; whole frames only.
    const Job *j = s.next_job(1, 0, true);
    EXPECT_TRUE(j->index == 1 && j->tiles == std::vector<int>{0});
}

TEST(Schedule, FrameDivisionKeepsTiles)
{
    Board s(make_tiles(kArea, 40), 6, Division::Frame);     // 4 x 3 tiles
    s.add_slave(1, 100);
    s.add_slave(2, 100);
    s.plan(2);
    std::map<int, std::vector<int>> first;
    for (int i = 0; i < 6; i++) {
        for (int slave : {1, 2}) {
            const Job *j = s.next_job(slave, i, true);
            EXPECT_TRUE(j && j->index == i);
            // Each slave keeps the tiles it had: its renderer's frame coherence stays valid.
            if (i == 0)
                first[slave] = j->tiles;
            else
                EXPECT_TRUE(j->tiles == first[slave]);
            deliver(s, *j);
        }
        // Both halves together are the frame, and it is complete now.
        EXPECT_TRUE(s.frame_done(i));
    }
    EXPECT_TRUE(first[1].size() == 6 && first[2].size() == 6);
    EXPECT_TRUE(s.all_done());
}

TEST(Schedule, WindowAndRebalance)
{
    Board s(make_tiles(kArea, 40), 40, Division::Frame);
    s.add_slave(1, 100);
    s.add_slave(2, 100);
    s.plan(1);
    const Job *slow = s.next_job(2, 0, true);     // slave 2 takes frame 0 and never returns
    EXPECT_TRUE(slow && slow->index == 0);
    int fast_jobs = 0;
    while (const Job *j = s.next_job(1, 0, true)) {
        s.note_speed(1, 1e6, 0.1);
        deliver(s, *j);
        fast_jobs++;
        EXPECT_TRUE(fast_jobs < 100);
    }
    // The fast slave waits once the range divided kWindow frames past the oldest unfinished.
    EXPECT_TRUE(fast_jobs == Schedule::kWindow);
    EXPECT_TRUE(s.frames_done() == 0);
    // Slave 2 catches up slowly; the next division gives the fast slave more tiles.
    s.note_speed(2, 1e5, 1.0);
    deliver(s, *slow);
    std::vector<int> mine;
    while (const Job *j = s.next_job(1, 1, true)) {
        mine = j->tiles;
        deliver(s, *j);
    }
    EXPECT_TRUE(mine.size() > 6);
}

// Without fc (moves are free): slaves 1 and 2, on hosts of their own.
static void two_slaves_without_fc(Board &s)
{
    s.set_cheap_moves(true);
    s.add_slave(1, 100);
    s.add_slave(2, 200);
}

// The last frames of a range without fc are divided so that the slaves finish together (the
// tests below render two frames, both in that tail); earlier ones go whole to one slave.
TEST(Schedule, CheapMovesBalanceTheLastFrames)
{
    Board s(make_tiles(kArea, 40), 2, Division::Frame);
    two_slaves_without_fc(s);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    Job first_a = *a;
    const Job *b = s.next_job(2, 0, true);
    Job first_b = *b;
    EXPECT_TRUE(first_a.tiles.size() == 6 && first_b.tiles.size() == 6);
    // Slave 1 renders twice as fast: without fc, the next frame it asks for gives it more.
    s.note_speed(1, 2e5, 1.0);
    s.note_speed(2, 1e5, 1.0);
    deliver(s, first_a);
    deliver(s, first_b);
    const Job *c = s.next_job(1, 1, true);
    EXPECT_TRUE(c && c->index == 1 && c->tiles.size() >= 7);
}

TEST(Schedule, CheapMovesDealEveryFrameAfresh)
{
    // Without fc a frame's tiles go out as if it were the first frame at the slaves' current
    // speeds, whoever had them before: spread over the frame, not the tiles nearest a
    // slave's old share.
    Board s(make_tiles(kArea, 40), 2, Division::Frame);
    two_slaves_without_fc(s);
    s.plan(1);
    Job a = *s.next_job(1, 0, true), b = *s.next_job(2, 0, true);
    s.note_speed(1, 3e5, 1.0);
    s.note_speed(2, 1e5, 1.0);
    deliver(s, a);
    deliver(s, b);
    std::vector<int> later = s.next_job(2, 1, true)->tiles;

    Board fresh(make_tiles(kArea, 40), 2, Division::Frame);
    two_slaves_without_fc(fresh);
    fresh.note_speed(1, 3e5, 1.0);
    fresh.note_speed(2, 1e5, 1.0);
    fresh.plan(1);
    fresh.next_job(1, 0, true);
    EXPECT_TRUE(later == fresh.next_job(2, 0, true)->tiles);
    EXPECT_TRUE(later.size() == 3 && later.front() < 6 && later.back() >= 6);
}

TEST(Schedule, CheapMovesLetSlavesFinishTogether)
{
    // Without fc a slave still busy with an earlier frame gets less of the next one: equal
    // speeds, but slave 2 has all of its frame-0 share (6 tiles of 1600 pixels, 0.096 s) to
    // go when slave 1 asks for frame 1. Both then finish frame 1 at 0.144 s: 9 tiles and 3.
    Board s(make_tiles(kArea, 40), 2, Division::Frame);
    two_slaves_without_fc(s);
    s.plan(1);
    Job a = *s.next_job(1, 0, true);
    EXPECT_TRUE(s.next_job(2, 0, true)->tiles.size() == 6);
    s.note_speed(1, 1e5, 1.0);
    s.note_speed(2, 1e5, 1.0);
    deliver(s, a);
    const Job *c = s.next_job(1, 0, true);
    EXPECT_TRUE(c && c->index == 1 && c->tiles.size() == 9);
}

TEST(Schedule, CheapMovesDealWholeFrames)
{
    // Without fc every frame but the last few goes whole to one slave: one parse a frame, not
    // one per slave. Slave 1 is three times as fast as slave 2; each keeps two jobs queued,
    // and the faster one finishes its jobs first.
    const int nframes = 20;
    Board s(make_tiles(kArea, 40), nframes, Division::Frame);   // 12 tiles a frame
    two_slaves_without_fc(s);
    s.plan(1);
    std::map<int, std::vector<Job>> queued;
    std::map<int, int> parses;      // frame -> jobs of it
    std::map<int, int> whole;       // slave -> whole frames rendered
    double t = 0;
    int steps = 0;
    while (!s.all_done() && steps++ < 1000) {
        for (int slave : {1, 2})
            while (queued[slave].size() < 2) {
                const Job *j = s.next_job(slave, t, false);
                if (!j)
                    break;
                queued[slave].push_back(*j);
                parses[j->index]++;
            }
        // Slave 1 delivers three jobs for each of slave 2's.
        int slave = (steps % 4 == 0 || queued[1].empty()) ? 2 : 1;
        if (queued[slave].empty())
            slave = 3 - slave;
        if (queued[slave].empty())
            break;
        Job j = queued[slave].front();
        queued[slave].erase(queued[slave].begin());
        double seconds = (slave == 1 ? 1.0 : 3.0) * double(j.tiles.size()) / 12;
        t += seconds / 2;
        s.note_speed(slave, double(j.tiles.size()) * 1600, seconds);
        if (j.tiles.size() == 12)
            whole[slave]++;
        deliver(s, j, nullptr, t);
    }
    EXPECT_TRUE(s.all_done());
    // Whole frames until the tail: at these speeds (3 : 1) the last four frames are divided.
    for (int i = 0; i < nframes - 4; i++)
        EXPECT_TRUE(parses[i] == 1);
    int divided = 0;
    for (int i = nframes - 4; i < nframes; i++)
        divided += parses[i] > 1;
    EXPECT_TRUE(divided >= 2);
    // The faster slave took more whole frames than the slower.
    EXPECT_TRUE(whole[1] > whole[2] && whole[2] > 0);
}

TEST(Schedule, CheapMovesDividedFramesKeepTheWindow)
{
    // Divided frames (the last ones) are held by the master until their last tile: while one
    // slave keeps its share of the oldest, the others divide at most kWindow frames (32
    // slaves of master-scale on 24 frames once held all 24).
    const int nframes = 12;
    Board s(make_tiles(kArea, 20), nframes, Division::Frame);     // 48 tiles
    s.set_cheap_moves(true);
    for (int slave = 1; slave <= 16; slave++)
        s.add_slave(slave, 100 * slave);
    s.plan(1);
    EXPECT_TRUE(s.next_job(16, 0, false) != nullptr);     // slave 16 never returns its first share
    for (int step = 0; step < 1000; step++) {
        bool any = false;
        for (int slave = 1; slave <= 15; slave++)
            if (const Job *j = s.next_job(slave, 0, false)) {
                deliver(s, *j);
                any = true;
            }
        if (!any)
            break;
    }
    int partial = partial_frames(s);
    EXPECT_TRUE(partial >= 1 && partial <= Schedule::kWindow);
}

TEST(Schedule, CheapMovesWindowFitsQueuedWholeFrames)
{
    // A slave that holds two whole frames does not stop the other at kWindow frames: whole
    // frames reach the master complete. Stuck for good, it still stops it a little later.
    Board s(make_tiles(kArea, 40), 40, Division::Frame);
    two_slaves_without_fc(s);
    s.plan(1);
    const Job *a = s.next_job(2, 0, true);
    const Job *b = s.next_job(2, 0, true);
    EXPECT_TRUE(a && b && a->tiles.size() == 12 && b->tiles.size() == 12);
    int fast_jobs = 0;
    while (const Job *j = s.next_job(1, 0, true)) {
        EXPECT_TRUE(j->tiles.size() == 12);
        deliver(s, *j);
        EXPECT_TRUE(++fast_jobs < 40);
    }
    EXPECT_TRUE(fast_jobs > Schedule::kWindow);
    EXPECT_TRUE(fast_jobs <= Schedule::kWindow + 4);
}

TEST(Schedule, MoreSlavesThanTiles)
{
    Board s(make_tiles(kArea, 80), 12, Division::Frame);     // 4 tiles
    for (int slave = 1; slave <= 6; slave++)
        s.add_slave(slave, 100 * slave);
    s.plan(1);
    // Four slaves share the frames' tiles; the other two take later frames of their own.
    std::set<int> busy;
    for (int slave = 1; slave <= 6; slave++)
        if (s.next_job(slave, 0, false))
            busy.insert(slave);
    EXPECT_TRUE(busy.size() == 6);
}

TEST(Schedule, ResumeSkipsDoneFrames)
{
    Board s({kArea}, 10, Division::Sequence);
    for (int i : {0, 1, 5})
        s.mark_frame(i);
    EXPECT_TRUE(s.frames_done() == 3);
    s.add_slave(1, 100);
    s.plan(1);
    std::vector<int> got;
    while (const Job *j = s.next_job(1, 0, false)) {
        got.push_back(j->index);
        deliver(s, *j);
    }
    // Finished frames get no job.
    EXPECT_TRUE((got == std::vector<int>{2, 3, 4, 6, 7, 8, 9}));
    EXPECT_TRUE(s.all_done());
}

TEST(Schedule, IdleSlaveSplitsRange)
{
    Board s({kArea}, 10, Division::Sequence);
    s.add_slave(1, 100);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    const Job *b = s.next_job(1, 0, true);
    EXPECT_TRUE(a->index == 0 && b->index == 1);
    // A second slave arrives: it takes the later half of what is not handed out (2..9).
    s.add_slave(2, 100);
    const Job *c = s.next_job(2, 0, true);
    EXPECT_TRUE(c && c->index == 6);
    std::set<int> one, two;
    for (int k = 0; k < 10; k++) {
        if (const Job *j = s.next_job(1, 0, false)) {
            one.insert(j->index);
            deliver(s, *j);
        }
        if (const Job *j = s.next_job(2, 0, false)) {
            two.insert(j->index);
            deliver(s, *j);
        }
    }
    // No frame is handed to both: the split needs no handshake.
    for (int i : one)
        EXPECT_TRUE(!two.count(i) && i < 6);
}

TEST(Schedule, HybridRangesAreShared)
{
    // Four slaves, two ranges: each range's frames are divided between two of them; a fifth
    // slave arriving later splits a range, as in sequence division.
    Board s(make_tiles(kArea, 40), 10, Division::Hybrid);     // 12 tiles
    for (int slave : {1, 2, 3, 4})
        s.add_slave(slave, 100);
    s.plan(2, 4);
    std::map<int, const Job *> first;
    for (int slave : {1, 2, 3, 4})
        first[slave] = s.next_job(slave, 0, true);
    std::map<int, int> tiles_of_frame;
    for (auto &kv : first) {
        EXPECT_TRUE(kv.second && kv.second->tiles.size() == 6);
        tiles_of_frame[kv.second->index] += int(kv.second->tiles.size());
    }
    // Frames 0 and 5 (the ranges' first frames), each divided between two slaves.
    EXPECT_TRUE(tiles_of_frame.size() == 2 && tiles_of_frame[0] == 12 && tiles_of_frame[5] == 12);
    s.add_slave(5, 100);
    const Job *late = s.next_job(5, 0, true);
    // The later half of the first range's undivided frames (1..4), whole frames.
    EXPECT_TRUE(late && late->tiles.size() == 12 && late->index == 3);
}

TEST(Schedule, FreshCostShortensSplits)
{
    // With fc a newcomer's first frame costs 5 coherent frames: of 9 undivided frames it
    // takes (9 + 1 - 5) / 2 = 2, so both finish together; of 4 it takes none.
    for (int frames : {11, 6}) {
        Board s({kArea}, frames, Division::Sequence);
        s.set_fresh_cost(5);
        s.add_slave(1, 100);
        s.plan(1, 1);
        s.next_job(1, 0, true);
        s.next_job(1, 0, true);     // frames 0 and 1 handed out
        s.add_slave(2, 100);
        const Job *c = s.next_job(2, 0, false);
        if (frames == 11) {
            EXPECT_TRUE(c && c->index == 9);
        } else {
            EXPECT_TRUE(c == nullptr);
        }
    }
}

// Slave renders the next `count` frames of its range, from index `first`, one job at a time.
static void finish_range(Board &s, int slave, int first, int count)
{
    std::vector<Job> cancel;
    for (int k = 0; k < count; k++) {
        const Job *j = s.next_job(slave, 0, true);
        EXPECT_TRUE(j && j->index == first + k);
        if (!j)
            return;
        int id = j->id, index = j->index;
        std::vector<int> tiles = j->tiles;
        job_done(s, id, index, tiles, cancel, 0);
    }
}

TEST(Schedule, JumpCostLengthensSplits)
{
    // Two ranges of 11 frames; the other slave has the first two of its range handed out,
    // 9 undivided. A slave that finished its range splits the other's. A range before its
    // own is a fresh start (5 coherent frames: a renderer cannot go back): it takes
    // (9 - 4) / 2 = 2 frames. A range after its own is a jump forward, with the renderer's
    // samples: before any jump was measured it is priced halfway, (1 + 5) / 2 = 3, and takes
    // (9 - 2) / 2 = 3 frames; once jumps were measured at 2 frames it takes (9 - 1) / 2 = 4;
    // a jump cost above the fresh one is not believed (5 again: 2 frames).
    for (bool forward : {true, false}) {
        for (double jump : {0.0, 2.0, 8.0}) {
            Board s({kArea}, 22, Division::Sequence);
            s.set_fresh_cost(5);
            if (jump > 0)
                s.set_jump_cost(jump);
            s.add_slave(1, 100);
            s.add_slave(2, 200);
            s.plan(2, 2);
            int done_first = forward ? 1 : 2, other = forward ? 2 : 1;
            int base = forward ? 0 : 11, other_base = forward ? 11 : 0;
            s.next_job(other, 0, true);
            s.next_job(other, 0, true);
            finish_range(s, done_first, base, 11);
            const Job *c = s.next_job(done_first, 0, false);
            int taken = !forward ? 2 : jump == 0.0 ? 3 : jump == 2.0 ? 4 : 2;
            EXPECT_TRUE(c && c->index == other_base + 11 - taken);
        }
    }
}

TEST(Schedule, SplitPrefersAForwardJump)
{
    // Three ranges of 11 frames. Slave 2 finished 11..21; slave 1 has 0 and 1 handed out (9
    // undivided, behind slave 2: a fresh start, worth (9 - 4) / 2 = 2 frames), slave 3 has
    // 22..25 (7 undivided, ahead: a jump of 2 frames, worth (7 - 1) / 2 = 3). The split takes
    // the 3 at the end of slave 3's range, not 2 of the range with more work.
    Board s({kArea}, 33, Division::Sequence);
    s.set_fresh_cost(5);
    s.set_jump_cost(2);
    for (int k = 1; k <= 3; k++)
        s.add_slave(k, 100 * k);
    s.plan(3, 3);
    s.next_job(1, 0, true);
    s.next_job(1, 0, true);
    for (int k = 0; k < 4; k++)
        s.next_job(3, 0, true);
    finish_range(s, 2, 11, 11);
    const Job *c = s.next_job(2, 0, false);
    EXPECT_TRUE(c && c->index == 30);
}

TEST(Schedule, SplitTakesTheNearestRangeAhead)
{
    // Three ranges of 11 frames. Slave 1 finished 0..10; slave 2 has 11..14 handed out (7
    // undivided, a jump of 2 frames is worth (7 - 1) / 2 = 3), slave 3 has 22 and 23 (9
    // undivided, worth 4). Slave 1 takes the 3 at the end of the nearer range, so that its
    // jump to slave 3's range later is forward again.
    Board s({kArea}, 33, Division::Sequence);
    s.set_fresh_cost(5);
    s.set_jump_cost(2);
    for (int k = 1; k <= 3; k++)
        s.add_slave(k, 100 * k);
    s.plan(3, 3);
    for (int k = 0; k < 4; k++)
        s.next_job(2, 0, true);
    s.next_job(3, 0, true);
    s.next_job(3, 0, true);
    finish_range(s, 1, 0, 11);
    const Job *c = s.next_job(1, 0, false);
    EXPECT_TRUE(c && c->index == 19);
}

TEST(Schedule, FasterNewcomerTakesMore)
{
    // fc, a fresh frame costs 5 coherent ones; the newcomer renders twice as fast: of 9
    // undivided frames it takes (9 * 2 - 4 * 1) / 3 = 4 (it finishes after 8/2 = 4 frame
    // times, the range's slave after 5).
    Board s({kArea}, 11, Division::Sequence);
    s.set_fresh_cost(5);
    s.add_slave(1, 100);
    s.plan(1, 1);
    s.next_job(1, 0, true);
    s.next_job(1, 0, true);
    s.note_speed(1, 1e5, 1.0);
    s.note_speed(2, 2e5, 1.0);
    s.add_slave(2, 200);
    const Job *c = s.next_job(2, 0, false);
    EXPECT_TRUE(c && c->index == 7);
}

TEST(Schedule, DeadSlaveOrphans)
{
    Board s(make_tiles(kArea, 80), 4, Division::Frame);
    s.add_slave(1, 100);
    s.add_slave(2, 200);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    int index = a->index;
    std::vector<int> tiles = a->tiles;
    std::vector<int> lost = s.remove_slave(1);
    EXPECT_TRUE(lost.size() == 1);
    // Its cells go first to the next slave that asks.
    const Job *b = s.next_job(2, 1, true);
    EXPECT_TRUE(b && b->index == index && b->tiles == tiles);
    EXPECT_TRUE(s.repair() == 0);
}

TEST(Schedule, FailureRetriesElsewhere)
{
    Board s({kArea}, 2, Division::Sequence);
    s.add_slave(1, 100);
    s.add_slave(2, 100);
    s.add_slave(3, 300);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    int index = a->index;
    EXPECT_TRUE(s.job_failed(a->id, 0) == 1);
    // Another slave on the same host does not get it while another host can.
    const Job *b = s.next_job(2, 0, true);
    EXPECT_TRUE(!b || b->index != index);
    const Job *c = s.next_job(3, 0, true);
    EXPECT_TRUE(c && c->index == index && c->failures == 1);
    EXPECT_TRUE(s.job_failed(c->id, 0) == 2);
    const Job *d = s.next_job(1, 0, true);
    EXPECT_TRUE(d && d->index == index);
    EXPECT_TRUE(s.job_failed(d->id, 0) == Schedule::kRetries);
}

TEST(Schedule, StragglerDuplicate)
{
    Board s({kArea}, 1, Division::Sequence);
    s.add_slave(1, 100);
    s.add_slave(2, 100);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    int aid = a->id;
    // Nothing else to do, but the job just started: no copy yet.
    EXPECT_TRUE(s.next_job(2, 0.5, true) == nullptr);
    const Job *b = s.next_job(2, 5, true);
    EXPECT_TRUE(b && b->dup_of == aid && b->index == 0);
    EXPECT_TRUE(s.next_job(2, 6, true) == nullptr);   // one copy only
    std::vector<Job> cancel;
    // The first result wins; the other copy has nothing left and is cancelled.
    EXPECT_TRUE(deliver(s, *b, &cancel) == std::vector<int>{0});
    EXPECT_TRUE(cancel.size() == 1 && cancel[0].id == aid);
    EXPECT_TRUE(s.all_done());
}

TEST(Schedule, QueuedJobIsNotAStraggler)
{
    Board s({kArea}, 2, Division::Sequence);
    s.add_slave(1, 100);
    s.plan(1);
    const Job *a = s.next_job(1, 0, true);
    Job first = *a;
    const Job *b = s.next_job(1, 0, true);
    int bid = b->id;
    s.add_slave(2, 100);
    // The straggler clock of a job starts when its slave begins it, not when it was sent.
    const Job *d = s.next_job(2, 5, true);
    EXPECT_TRUE(d && d->dup_of == first.id);
    deliver(s, first, nullptr, 5);  // slave 1 now renders b; the copy of a is cancelled
    s.remove_slave(2);
    s.add_slave(3, 100);
    EXPECT_TRUE(s.next_job(3, 5.5, true) == nullptr);
    const Job *e = s.next_job(3, 30, true);
    EXPECT_TRUE(e && e->dup_of == bid);
}

TEST(Schedule, Repair)
{
    Board s(make_tiles(kArea, 80), 4, Division::Frame);
    s.add_slave(1, 100);
    s.plan(1);
    EXPECT_TRUE(s.repair() == 0);     // the plan covers everything
}

// Random slaves of random speeds render, die, fail and join; the work always completes,
// every missing cell stays covered, no cell is delivered twice without duplicates, and the
// master holds few jobs and (frame division) few partial frames.
static void simulate(Division div, unsigned seed, bool cheap_moves = false)
{
    std::mt19937 rng(seed);
    std::vector<Rect> tiles = div == Division::Sequence ? std::vector<Rect>{kArea}
                                                        : make_tiles(kArea, 40);
    const int nframes = 23;
    Board s(tiles, nframes, div);
    s.set_cheap_moves(cheap_moves);
    std::map<int, double> speed;
    for (int slave = 1; slave <= 3; slave++) {
        s.add_slave(slave, 100 * (1 + slave % 2));
        speed[slave] = 1 + double(rng() % 3);
    }
    s.plan(div == Division::Frame ? 1 : 3, 3);
    std::map<int, std::vector<Job>> held;
    int next_slave = 4, steps = 0, max_partial = 0;
    std::map<std::pair<int, int>, int> delivered;
    while (!s.all_done() && steps++ < 20000) {
        for (auto &kv : speed) {
            int slave = kv.first;
            while (held[slave].size() < 2) {
                const Job *j = s.next_job(slave, steps, false);
                if (!j)
                    break;
                held[slave].push_back(*j);
            }
        }
        EXPECT_TRUE(s.repair() == 0);
        EXPECT_TRUE(int(s.jobs().size()) <= 2 * int(speed.size()));
        std::vector<int> busy;
        for (auto &kv : held)
            if (!kv.second.empty())
                busy.push_back(kv.first);
        if (busy.empty())
            break;
        int slave = busy[rng() % busy.size()];
        if (rng() % 10 >= speed[slave] * 3)
            continue;   // slow slaves finish less often
        Job j = held[slave].front();
        held[slave].erase(held[slave].begin());
        int roll = int(rng() % 40);
        if (roll == 0) {
            // The slave dies; a new one joins.
            s.remove_slave(slave);
            held.erase(slave);
            speed.erase(slave);
            s.add_slave(next_slave, 100 * next_slave);
            speed[next_slave++] = 1 + double(rng() % 3);
            continue;
        }
        if (roll == 1 && j.failures < Schedule::kRetries - 1) {
            s.job_failed(j.id, 0);
            continue;
        }
        s.note_speed(slave, double(j.tiles.size()) * 1600, 1.0 / speed[slave]);
        for (int t : deliver(s, j))
            delivered[{j.index, t}]++;
        max_partial = std::max(max_partial, partial_frames(s));
    }
    EXPECT_TRUE(s.all_done());
    EXPECT_TRUE(int(delivered.size()) == nframes * s.tiles());
    for (auto &kv : delivered)
        EXPECT_TRUE(kv.second == 1);
    // Frame division completes frames in order: the master holds a few partial frames.
    if (div == Division::Frame) {
        EXPECT_TRUE(max_partial <= Schedule::kWindow + 2);
    }
}

// Many random runs of each division, with and without fc's costly moves.
TEST(Schedule, SimulationsCompleteEveryCellOnce)
{
    for (unsigned seed = 1; seed <= 50; seed++) {
        simulate(Division::Sequence, seed);
        simulate(Division::Frame, seed);
        simulate(Division::Hybrid, seed);
        simulate(Division::Frame, seed, true);
        simulate(Division::Hybrid, seed, true);
    }
}

// A stalled job (its slave stopped, its renderer hung) gets a copy on the next slave that asks,
// before the range's own work; its slave gets nothing more until the job is over, and its
// queued job and its share of the range go to the others.
TEST(Schedule, AStalledJobIsCopiedAtOnceAndItsSlaveSuspended)
{
    Board s(make_tiles(kArea, 80), 12, Division::Frame);     // 4 tiles
    s.add_slave(1, 100);
    s.add_slave(2, 200);
    s.plan(1);
    const Job *a1 = s.next_job(1, 0, true);
    const Job *a2 = s.next_job(1, 0, true);
    const Job *b1 = s.next_job(2, 0, true);
    ASSERT_TRUE(a1 && a2 && b1);
    int stalled = a1->id, queued = a2->id, frame0 = a1->index;
    std::vector<int> queued_tiles = a2->tiles;
    int queued_index = a2->index;
    deliver(s, *b1, nullptr, 1);
    std::vector<Job> cancel;
    s.stall(stalled, cancel);
    ASSERT_EQ(cancel.size(), 1u);
    EXPECT_EQ(cancel[0].id, queued);
    EXPECT_TRUE(s.suspended(1));
    EXPECT_FALSE(s.suspended(2));
    EXPECT_EQ(s.next_job(1, 2, true), nullptr);     // nothing for a suspended slave
    // Slave 2 gets the queued job's cells back first (orphans), then the copy.
    const Job *o = s.next_job(2, 2, true);
    ASSERT_TRUE(o);
    EXPECT_EQ(o->index, queued_index);
    EXPECT_EQ(o->tiles, queued_tiles);
    EXPECT_EQ(o->dup_of, -1);
    const Job *copy = s.next_job(2, 2, true);
    ASSERT_TRUE(copy);
    EXPECT_EQ(copy->dup_of, stalled);
    EXPECT_EQ(copy->index, frame0);
    // Its slave speaking while the job still stalls changes nothing.
    EXPECT_FALSE(s.resume(1));
    // The copy's result cancels the stalled job; its slave stays suspended until it speaks (a
    // stopped slave never does), then is free again.
    std::vector<Job> cancelled;
    deliver(s, *copy, &cancelled, 3);
    ASSERT_EQ(cancelled.size(), 1u);
    EXPECT_EQ(cancelled[0].id, stalled);
    EXPECT_TRUE(s.frame_done(frame0));
    EXPECT_TRUE(s.suspended(1));
    EXPECT_EQ(s.next_job(1, 4, true), nullptr);
    EXPECT_TRUE(s.resume(1));
    EXPECT_FALSE(s.suspended(1));
    const Job *back = s.next_job(1, 4, true);
    ASSERT_TRUE(back);
    EXPECT_GT(back->index, frame0);
}

// The copy goes to another host's slave when there is one; with none, to any other slave.
TEST(Schedule, AStalledJobIsCopiedOnAnotherHostFirst)
{
    Board s({kArea}, 4, Division::Sequence);
    s.add_slave(1, 100);
    s.add_slave(2, 100);    // the stalled slave's host
    s.add_slave(3, 300);
    s.plan(3);
    const Job *j = s.next_job(1, 0, true);
    ASSERT_TRUE(j);
    int stalled = j->id;
    // Slaves 2 and 3 busy with their own ranges: two jobs each.
    for (int slave : {2, 3})
        while (s.live_jobs(slave) < 2 && s.next_job(slave, 0, true)) {
        }
    std::vector<Job> cancel;
    s.stall(stalled, cancel);
    // Slave 2 (same host) gets no copy while slave 3 can have it.
    const Job *k = s.next_job(2, 1, true);
    EXPECT_TRUE(k == nullptr || k->dup_of != stalled);
    const Job *copy = s.next_job(3, 1, true);
    ASSERT_TRUE(copy);
    EXPECT_EQ(copy->dup_of, stalled);
}

// A frame that needs no more work (given up) cancels its live jobs.
TEST(Schedule, ASettledFrameCancelsItsJobs)
{
    Board s(make_tiles(kArea, 80), 2, Division::Frame);
    s.add_slave(1, 100);
    s.plan(1);
    const Job *j = s.next_job(1, 0, true);
    ASSERT_TRUE(j);
    int id = j->id, index = j->index;
    s.mark_frame(index);
    std::vector<Job> cancel;
    s.frame_settled(index, cancel, 1);
    ASSERT_EQ(cancel.size(), 1u);
    EXPECT_EQ(cancel[0].id, id);
    EXPECT_EQ(s.live_jobs(1), 0);
}
