// report_test.cpp - what fc-master shows: the live display cut to the terminal's width, and
// an end summary that fits 80 columns whatever its numbers and names.
#include <gtest/gtest.h>

#include "report.h"

using namespace fc;

namespace {

std::vector<std::string> lines_of(const std::string &text)
{
    std::vector<std::string> out;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t nl = text.find('\n', pos);
        out.push_back(text.substr(pos, nl - pos));
        pos = nl == std::string::npos ? text.size() : nl + 1;
    }
    return out;
}

RunSummary a_long_run()
{
    RunSummary r;
    r.ok = false;
    r.error = "cannot write frame 17";
    r.elapsed = 3725;
    r.rendered = 1234;
    r.resumed = 5678;
    r.total = 9999;
    r.retried = 12;
    r.division = "sequence";
    r.virtual_machine = "private";
    r.frame_seconds = {1.25, 123.4, 7.5};
    r.frame_numbers = {1, 2, 1000};
    r.savings.known = true;
    r.savings.rays_spent = 1.23e9;
    r.savings.rays_full = 9.87e9;
    r.savings.seconds_spent = 1234.5;
    r.savings.seconds_full = 98765.4;
    HostStat h;
    h.name = "a-host-name-longer-than-sixteen.example.org";
    h.slaves = 64;
    h.jobs = 99999;
    h.frames = 9999;
    h.tiles = 999999;
    h.rays = 9.87e12;
    h.busy = 99 * 3600;
    h.pixels = 1e13;
    h.excluded = true;
    r.hosts[h.name] = h;
    h.name = "fch1";
    r.hosts[h.name] = h;
    return r;
}

} // namespace

TEST(Report, TheSummaryFitsEightyColumns)
{
    Report report(10, true);
    std::string text = report.summary(a_long_run());
    for (const std::string &line : lines_of(text))
        EXPECT_LT(line.size(), size_t(Report::kSummaryColumns)) << line;
    EXPECT_NE(text.find("fc-master: failed with 6912 of 9999 frame(s) done"), std::string::npos)
        << text;
    EXPECT_NE(text.find("frame time: median 7.50 s, fastest 1.25 s, slowest 123 s (frame 2)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  a-host-name-longer-than-sixteen.example.org\n"), std::string::npos);
    EXPECT_NE(text.find("(left out after failures)"), std::string::npos);
}

TEST(Report, FramesGivenUpAreListed)
{
    RunSummary r;
    r.ok = false;
    r.rendered = 7;
    r.total = 9;
    r.division = "frame";
    r.virtual_machine = "private";
    r.given_up = {{3, "frame 3 hangs"}, {8, "Parse Error"}};
    std::string text = Report(10, true).summary(r);
    EXPECT_NE(text.find("fc-master: 7 frame(s) rendered, 0 already present, 2 failed"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("frames without a file (their messages above): 3, 8"), std::string::npos);
}

TEST(Report, TheLiveDisplayIsCutToTheTerminal)
{
    ProgressState p;
    p.frames_todo = 100;
    p.frames_done = 40;
    p.fraction = 0.4;
    p.elapsed = 30;
    p.eta = 45;
    p.in_flight = {41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 51, 52, 53, 54, 55, 56};
    p.slaves = 3;
    p.busy = 3;
    HostProgress h;
    h.name = "fch1";
    h.slaves = 3;
    h.busy = 3;
    h.pixels = 1e7;
    p.hosts = {h};
    for (int columns : {40, 60, 80}) {
        std::vector<std::string> lines = Report::display(p, columns, 24);
        ASSERT_EQ(lines.size(), 3u);
        for (const std::string &line : lines)
            EXPECT_LT(int(line.size()), columns) << line;
        EXPECT_NE(lines[0].find("40%"), std::string::npos) << lines[0];
    }
}
