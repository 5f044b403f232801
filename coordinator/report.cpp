// report.cpp - progress lines or bar, end summary, --stats JSON.
#include "report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util.h"

namespace fc {

Report::Report(double interval, bool quiet)
    : tty_(isatty(2) != 0), quiet_(quiet), interval_(interval)
{
}

std::string Report::duration(double s)
{
    if (s < 0 || !std::isfinite(s))
        return "-";
    long t = long(s + 0.5);
    if (t >= 3600)
        return strf("%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
    return strf("%ld:%02ld", t / 60, t % 60);
}

void Report::progress(double elapsed, int frames_done, int frames_total, double fraction, int busy,
                      int slaves)
{
    if (quiet_)
        return;
    double every = tty_ ? 0.25 : interval_;
    if (every <= 0 || elapsed - last_ < every)
        return;
    last_ = elapsed;
    std::string eta = "-";
    if (fraction > 0.02 && fraction < 1)
        eta = duration(elapsed * (1 - fraction) / fraction);
    if (tty_) {
        const int width = 30;
        int filled = int(fraction * width + 0.5);
        std::string bar(size_t(filled), '#');
        bar.append(size_t(width - filled), '.');
        fprintf(stderr, "\r[%s] %3.0f%%  %d/%d frames  %d/%d slaves busy  %s  ETA %s ",
                bar.c_str(), fraction * 100, frames_done, frames_total, busy, slaves,
                duration(elapsed).c_str(), eta.c_str());
        bar_open_ = true;
    } else {
        fprintf(stderr, "fc-master: %d/%d frames (%.0f%%), %d/%d slaves busy, %s elapsed, ETA %s\n",
                frames_done, frames_total, fraction * 100, busy, slaves,
                duration(elapsed).c_str(), eta.c_str());
    }
    fflush(stderr);
}

void Report::clear_line()
{
    if (bar_open_) {
        fprintf(stderr, "\r\033[K");
        bar_open_ = false;
    }
}

std::string Report::summary(double elapsed, int rendered, int resumed, const std::string &division,
                            const std::map<std::string, HostStat> &hosts) const
{
    std::string s = strf("fc-master: %d frame(s) rendered", rendered);
    if (resumed)
        s += strf(", %d already present", resumed);
    s += strf(" in %s, %s division\n", duration(elapsed).c_str(), division.c_str());
    s += strf("  %-20s %6s %6s %7s %7s %14s %10s\n", "host", "slaves", "jobs", "frames",
              "tiles", "rays", "busy");
    for (auto &kv : hosts) {
        const HostStat &h = kv.second;
        s += strf("  %-20s %6d %6d %7d %7d %14.0f %10s%s\n", h.name.c_str(), h.slaves, h.jobs,
                  h.frames, h.tiles, h.rays, duration(h.busy).c_str(),
                  h.excluded ? "  (left out after failures)" : "");
    }
    return s;
}

std::string Report::json_string(const std::string &in)
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

bool Report::write_json(const std::string &path, const std::string &json_head,
                        const std::vector<FrameStat> &frames, const std::map<int, JobStat> &jobs,
                        const std::map<std::string, HostStat> &hosts, std::string &err) const
{
    std::string j = "{\n" + json_head;
    j += "  \"frames\": [\n";
    for (size_t i = 0; i < frames.size(); i++) {
        const FrameStat &f = frames[i];
        std::vector<std::string> host_list;
        for (const CellStat &c : f.cells)
            if (std::find(host_list.begin(), host_list.end(), c.host) == host_list.end())
                host_list.push_back(c.host);
        std::string hosts_json;
        for (size_t k = 0; k < host_list.size(); k++)
            hosts_json += (k ? ", " : "") + json_string(host_list[k]);
        j += strf("    {\"frame\": %d, \"file\": %s, \"resumed\": %s, \"host\": %s, \"hosts\": [%s], "
                 "\"rays\": %.0f, \"time\": %.3f, \"parses\": %d, \"finished_at\": %.3f, \"tiles\": [",
                 f.frame, json_string(f.file).c_str(), f.resumed ? "true" : "false",
                 host_list.empty() ? "null" : json_string(host_list[0]).c_str(),
                 hosts_json.c_str(), f.rays, f.seconds, f.parses, f.finished_at);
        for (size_t k = 0; k < f.cells.size(); k++) {
            const CellStat &c = f.cells[k];
            j += strf("%s{\"tile\": %d, \"job\": %d, \"host\": %s}", k ? ", " : "", c.tile,
                      c.job, json_string(c.host).c_str());
        }
        j += strf("]}%s\n", i + 1 < frames.size() ? "," : "");
    }
    j += "  ],\n  \"jobs\": [\n";
    size_t n = 0;
    for (auto &kv : jobs) {
        const JobStat &u = kv.second;
        std::string tiles;
        for (size_t k = 0; k < u.tiles.size(); k++)
            tiles += strf("%s%d", k ? ", " : "", u.tiles[k]);
        j += strf("    {\"id\": %d, \"frame\": %d, \"tiles\": [%s], \"host\": %s, \"tid\": \"t%x\", "
                 "\"duplicate_of\": %s, \"status\": %s, \"rays\": %.0f, \"parse\": %.4f, "
                 "\"trace\": %.4f}%s\n",
                 u.id, u.frame, tiles.c_str(), json_string(u.host).c_str(), unsigned(u.tid),
                 u.dup_of >= 0 ? strf("%d", u.dup_of).c_str() : "null",
                 json_string(u.status).c_str(), u.rays, u.parse, u.trace,
                 ++n < jobs.size() ? "," : "");
    }
    j += "  ],\n  \"hosts\": [\n";
    n = 0;
    for (auto &kv : hosts) {
        const HostStat &h = kv.second;
        j += strf("    {\"name\": %s, \"slaves\": %d, \"jobs\": %d, \"frames\": %d, "
                 "\"tiles\": %d, \"failures\": %d, \"excluded\": %s, \"rays\": %.0f, "
                 "\"busy\": %.3f}%s\n",
                 json_string(h.name).c_str(), h.slaves, h.jobs, h.frames, h.tiles, h.failures,
                 h.excluded ? "true" : "false", h.rays, h.busy, ++n < hosts.size() ? "," : "");
    }
    j += "  ]\n}\n";
    std::string tmp = path + ".tmp";
    if (!write_text(tmp, j, err))
        return false;
    if (rename(tmp.c_str(), path.c_str()) != 0)
        return sys_fail(err, "rename " + tmp);
    return true;
}

} // namespace fc
