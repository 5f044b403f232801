// run_stats.cpp - the run's statistics and the --stats JSON (see run_stats.h).
#include "run_stats.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>

#include "files.h"
#include "text.h"

namespace fc {

namespace {

std::string json_string(const std::string &in)
{
    std::string out = "\"";
    for (unsigned char c : in) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        case '\r': out += "\\r"; break;
        default:
            if (c < 0x20)
                out += strf("\\u%04x", c);
            else
                out += char(c);
        }
    }
    return out + "\"";
}

const char *json_bool(bool b)
{
    return b ? "true" : "false";
}

} // namespace

void RunStats::set_frames(const std::vector<int> &numbers, const std::vector<std::string> &files)
{
    frames_.assign(numbers.size(), FrameStat());
    for (size_t i = 0; i < numbers.size(); i++) {
        frames_[i].frame = numbers[i];
        frames_[i].file = files[i];
    }
}

HostStat &RunStats::host(const std::string &name)
{
    HostStat &h = hosts_[name];
    h.name = name;
    return h;
}

double RunStats::host_pixels(const std::string &name) const
{
    auto it = hosts_.find(name);
    return it == hosts_.end() ? 0 : it->second.pixels;
}

void RunStats::frames_held(size_t n)
{
    max_frames_held_ = std::max(max_frames_held_, int(n));
}

void RunStats::slaves_started(const std::string &name, int count)
{
    host(name).slaves += count;
}

void RunStats::host_failed(const std::string &name)
{
    host(name).failures++;
}

void RunStats::host_left_out(const std::string &name)
{
    host(name).excluded = true;
}

void RunStats::frame_written(int index, double seconds_after_start)
{
    frames_[size_t(index)].finished_at = seconds_after_start;
}

void RunStats::job_sent(const Job &job, int frame, const std::string &name, int tid)
{
    host(name).jobs++;
    if (!keep_jobs_)
        return;
    JobStat &js = jobs_[job.id];
    js.id = job.id;
    js.frame = frame;
    js.tiles = job.tiles;
    js.host = name;
    js.tid = tid;
    js.dup_of = job.dup_of;
}

void RunStats::job_ended(int id, const char *status)
{
    auto it = jobs_.find(id);
    if (it != jobs_.end())
        it->second.status = status;
}

void RunStats::result(const FrameResult &fr, int index, const std::vector<int> &fresh,
                      const std::string &name)
{
    double seconds = fr.parse_seconds + fr.trace_seconds;
    HostStat &hs = host(name);
    hs.tiles += int(fr.tiles.size());
    hs.rays += std::max(0.0, fr.rays);
    hs.busy += seconds;
    for (const Rect &r : fr.rects)
        hs.pixels += double(r.area());
    host_frames_[name].insert(fr.frame);
    auto js = jobs_.find(fr.job);
    if (js != jobs_.end()) {
        js->second.status = fresh.empty() ? "duplicate" : "done";
        js->second.rays = fr.rays;
        js->second.parse = fr.parse_seconds;
        js->second.trace = fr.trace_seconds;
    }
    if (fresh.empty())
        return;
    FrameStat &fs = frames_[size_t(index)];
    fs.rays += std::max(0.0, fr.rays);
    fs.seconds += seconds;
    fs.parses++;
    for (int t : fresh)
        fs.cells.push_back(CellStat{t, fr.job, name});
}

int RunStats::frames_retried() const
{
    int n = 0;
    for (const FrameStat &f : frames_)
        n += !f.resumed && f.retried;
    return n;
}

RunSummary RunStats::summary(const RunFacts &facts) const
{
    RunSummary r;
    r.ok = facts.ok;
    r.error = facts.error;
    r.elapsed = facts.elapsed;
    r.rendered = facts.rendered;
    r.resumed = facts.resumed;
    r.skipped = facts.skipped;
    r.total = facts.total;
    r.division = division_name(facts.division);
    r.virtual_machine = facts.virtual_machine;
    r.hosts = hosts_;
    for (auto &kv : r.hosts) {
        auto it = host_frames_.find(kv.first);
        kv.second.frames = it == host_frames_.end() ? 0 : int(it->second.size());
    }
    r.retried = frames_retried();
    for (const FrameStat &f : frames_)
        if (!f.resumed && f.finished_at >= 0) {
            r.frame_seconds.push_back(f.seconds);
            r.frame_numbers.push_back(f.frame);
        }
    r.given_up = facts.given_up;
    r.lost = facts.ok ? 0 : r.total - r.rendered - r.resumed - r.skipped - int(r.given_up.size());
    r.savings = facts.savings;
    return r;
}

std::string RunStats::json(const RunFacts &facts) const
{
    RunSummary sum = summary(facts);
    std::string j = "{\n";
    j += "  \"scene\": " + json_string(facts.scene) + ",\n";
    j += "  \"renderer\": " + json_string(facts.renderer) + ",\n";
    j += "  \"output\": " + json_string(facts.output) + ",\n";
    j += strf("  \"division\": \"%s\",\n", division_name(facts.division));
    j += strf("  \"tile\": %d,\n  \"tiles\": %d,\n  \"width\": %d,\n  \"height\": %d,\n",
              facts.tile, int(facts.tiles.size()), facts.width, facts.height);
    std::string rects;
    for (size_t k = 0; k < facts.tiles.size(); k++)
        rects += strf("%s[%d, %d, %d, %d]", k ? ", " : "", facts.tiles[k].x0, facts.tiles[k].y0,
                      facts.tiles[k].x1, facts.tiles[k].y1);
    j += "  \"tile_rects\": [" + rects + "],\n";
    j += strf("  \"max_frames_held\": %d,\n", max_frames_held_);
    j += strf("  \"frame_coherence\": %s,\n", json_bool(facts.frame_coherence));
    j += strf("  \"virtual_machine\": \"%s\",\n  \"hosts_used\": %d,\n",
              facts.virtual_machine.c_str(), int(hosts_.size()));
    j += strf("  \"format\": %s,\n  \"bits_per_color\": %d,\n", json_string(facts.format).c_str(),
              facts.bits_per_color);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    double cpu = double(ru.ru_utime.tv_sec) + ru.ru_utime.tv_usec / 1e6 +
                 double(ru.ru_stime.tv_sec) + ru.ru_stime.tv_usec / 1e6;
    j += strf("  \"master_cpu\": %.3f,\n  \"master_max_rss_kb\": %ld,\n", cpu, long(ru.ru_maxrss));
    j += strf("  \"messages\": %ld,\n", messages_);
    j += strf("  \"success\": %s,\n", json_bool(facts.ok));
    j += strf("  \"elapsed\": %.3f,\n", facts.elapsed);
    j += strf("  \"frames_total\": %d,\n  \"frames_rendered\": %d,\n  \"frames_resumed\": %d,\n",
              facts.total, facts.rendered, facts.resumed);
    j += strf("  \"frames_retried\": %d,\n  \"frames_lost\": %d,\n  \"frames_skipped\": %d,\n",
              sum.retried, sum.lost, sum.skipped);
    j += "  \"error\": " + (facts.ok ? std::string("null") : json_string(facts.error)) + ",\n";
    j += strf("  \"frames_failed\": %zu,\n", facts.given_up.size());
    const Savings &v = facts.savings;
    if (v.known)
        j += strf("  \"fc_saved\": {\"rays_spent\": %.0f, \"rays_without_fc\": %.0f, "
                  "\"trace_seconds_spent\": %.3f, \"trace_seconds_first_frame_rate\": %.3f},\n",
                  v.rays_spent, v.rays_full, v.seconds_spent, v.seconds_full);
    else
        j += "  \"fc_saved\": null,\n";

    j += "  \"frames\": [\n";
    for (size_t i = 0; i < frames_.size(); i++) {
        const FrameStat &f = frames_[i];
        std::vector<std::string> host_list;
        for (const CellStat &c : f.cells)
            if (std::find(host_list.begin(), host_list.end(), c.host) == host_list.end())
                host_list.push_back(c.host);
        std::string hosts_json;
        for (size_t k = 0; k < host_list.size(); k++)
            hosts_json += (k ? ", " : "") + json_string(host_list[k]);
        std::string failed = "null";
        for (auto &g : facts.given_up)
            if (g.first == f.frame)
                failed = json_string(g.second);
        j += strf("    {\"frame\": %d, \"file\": %s, \"resumed\": %s, \"retried\": %s, "
                  "\"failed\": %s, "
                  "\"host\": %s, \"hosts\": [%s], \"rays\": %.0f, \"time\": %.3f, \"parses\": %d, "
                  "\"finished_at\": %.3f, \"tiles\": [",
                  f.frame, json_string(f.file).c_str(), json_bool(f.resumed), json_bool(f.retried),
                  failed.c_str(),
                  host_list.empty() ? "null" : json_string(host_list[0]).c_str(),
                  hosts_json.c_str(), f.rays, f.seconds, f.parses, f.finished_at);
        for (size_t k = 0; k < f.cells.size(); k++) {
            const CellStat &c = f.cells[k];
            j += strf("%s{\"tile\": %d, \"job\": %d, \"host\": %s}", k ? ", " : "", c.tile,
                      c.job, json_string(c.host).c_str());
        }
        j += strf("]}%s\n", i + 1 < frames_.size() ? "," : "");
    }
    j += "  ],\n  \"jobs\": [\n";
    size_t n = 0;
    for (auto &kv : jobs_) {
        const JobStat &u = kv.second;
        std::string tiles;
        for (size_t k = 0; k < u.tiles.size(); k++)
            tiles += strf("%s%d", k ? ", " : "", u.tiles[k]);
        // A job still running when the run ended was stopped with it.
        const std::string status = u.status == "running" ? "stopped" : u.status;
        j += strf("    {\"id\": %d, \"frame\": %d, \"tiles\": [%s], \"host\": %s, \"tid\": \"t%x\", "
                  "\"duplicate_of\": %s, \"status\": %s, \"rays\": %.0f, \"parse\": %.4f, "
                  "\"trace\": %.4f}%s\n",
                  u.id, u.frame, tiles.c_str(), json_string(u.host).c_str(), unsigned(u.tid),
                  u.dup_of >= 0 ? strf("%d", u.dup_of).c_str() : "null",
                  json_string(status).c_str(), u.rays, u.parse, u.trace,
                  ++n < jobs_.size() ? "," : "");
    }
    j += "  ],\n  \"hosts\": [\n";
    n = 0;
    for (auto &kv : sum.hosts) {
        const HostStat &h = kv.second;
        j += strf("    {\"name\": %s, \"slaves\": %d, \"jobs\": %d, \"frames\": %d, "
                  "\"tiles\": %d, \"failures\": %d, \"excluded\": %s, \"rays\": %.0f, "
                  "\"busy\": %.3f, \"pixels\": %.0f}%s\n",
                  json_string(h.name).c_str(), h.slaves, h.jobs, h.frames, h.tiles, h.failures,
                  json_bool(h.excluded), h.rays, h.busy, h.pixels,
                  ++n < sum.hosts.size() ? "," : "");
    }
    j += "  ]\n}\n";
    return j;
}

bool RunStats::write_json(const std::string &path, const RunFacts &facts, std::string &err) const
{
    std::string tmp = path + ".tmp";
    if (!write_text(tmp, json(facts), err))
        return false;
    if (rename(tmp.c_str(), path.c_str()) != 0)
        return sys_fail(err, "rename " + tmp);
    return true;
}

} // namespace fc
