// run_stats_test.cpp - the run's statistics: counted as results arrive, summed up for the
// summary, and written as the --stats JSON.
#include <gtest/gtest.h>

#include "files.h"
#include "run_stats.h"
#include "temp_dirs.h"

using namespace fc;

namespace {

FrameResult result(int job, int frame, std::vector<int> tiles, double rays)
{
    FrameResult r;
    r.job = job;
    r.frame = frame;
    r.tiles = tiles;
    for (size_t k = 0; k < tiles.size(); k++)
        r.rects.push_back(Rect{0, 0, 10, 10});
    r.rays = rays;
    r.parse_seconds = 0.5;
    r.trace_seconds = 1.5;
    return r;
}

} // namespace

TEST(RunStats, ResultsCountPerFrameJobAndHost)
{
    RunStats s(true);
    s.set_frames({1, 2}, {"clk1.tga", "clk2.tga"});
    Job job;
    job.id = 7;
    job.tiles = {0, 1};
    s.job_sent(job, 1, "h1", 0x40001);
    s.slaves_started("h1", 1);
    s.result(result(7, 1, {0, 1}, 100), 0, {0, 1}, "h1");
    s.result(result(8, 1, {1}, 50), 0, {}, "h2");     // a duplicate that came second
    s.frame_written(0, 3.5);
    s.frame_resumed(1);
    RunFacts f;
    f.total = 2;
    f.rendered = 1;
    f.resumed = 1;
    RunSummary sum = s.summary(f);
    ASSERT_EQ(sum.hosts.size(), 2u);
    EXPECT_EQ(sum.hosts["h1"].tiles, 2);
    EXPECT_EQ(sum.hosts["h1"].frames, 1);
    EXPECT_DOUBLE_EQ(sum.hosts["h1"].busy, 2.0);
    EXPECT_DOUBLE_EQ(sum.hosts["h2"].pixels, 100);
    EXPECT_EQ(sum.frame_seconds, std::vector<double>{2.0});   // only the accepted job
    EXPECT_EQ(sum.frame_numbers, std::vector<int>{1});
    EXPECT_EQ(sum.lost, 0);

    std::string dir, err;
    ASSERT_TRUE(make_temp_dir("/tmp", "fc-run-stats-test-", dir, err)) << err;
    ASSERT_TRUE(s.write_json(dir + "/stats.json", f, err)) << err;
    std::string json;
    ASSERT_TRUE(read_text(dir + "/stats.json", json, err));
    EXPECT_NE(json.find("\"frames_total\": 2,"), std::string::npos);
    EXPECT_NE(json.find("{\"id\": 7, \"frame\": 1, \"tiles\": [0, 1], \"host\": \"h1\", "
                        "\"tid\": \"t40001\", \"duplicate_of\": null, \"status\": \"done\""),
              std::string::npos)
        << json;
    EXPECT_NE(json.find("\"tiles\": [{\"tile\": 0, \"job\": 7, \"host\": \"h1\"}, "
                        "{\"tile\": 1, \"job\": 7, \"host\": \"h1\"}]"),
              std::string::npos)
        << json;
    EXPECT_NE(json.find("\"fc_saved\": null"), std::string::npos);
    remove_tree(dir);
}

TEST(RunStats, AFailedRunCountsItsLostFrames)
{
    RunStats s(false);
    s.set_frames({1, 2, 3}, {"a1", "a2", "a3"});
    s.frame_retried(2);
    RunFacts f;
    f.ok = false;
    f.error = "disk full";
    f.total = 3;
    f.rendered = 1;
    RunSummary sum = s.summary(f);
    EXPECT_EQ(sum.lost, 2);
    EXPECT_EQ(sum.retried, 1);
    EXPECT_EQ(sum.error, "disk full");
}
