// report.cpp - progress display or lines, end summary (see report.h).
#include "report.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "files.h"
#include "text.h"

namespace fc {

namespace {

// Cut a line to fit in `columns` (one column is left free: writing the last one makes some
// terminals wrap).
std::string fit(const std::string &s, int columns)
{
    size_t room = size_t(std::max(1, columns - 1));
    return s.size() <= room ? s : s.substr(0, room);
}

std::string rate(double pixels_per_second, double frame_pixels)
{
    std::string px = pixels_per_second >= 1e6 ? strf("%.1f Mpx/s", pixels_per_second / 1e6)
                                              : strf("%.0f kpx/s", pixels_per_second / 1e3);
    double fpm = frame_pixels > 0 ? pixels_per_second / frame_pixels * 60 : 0;
    return px + (fpm >= 10 ? strf(" (%.0f frames/min)", fpm) : strf(" (%.1f frames/min)", fpm));
}

std::string frame_list(const std::vector<int> &frames, size_t room)
{
    std::string s;
    for (size_t k = 0; k < frames.size(); k++) {
        std::string next = (k ? " " : "") + std::to_string(frames[k]);
        if (s.size() + next.size() > room) {
            s += strf(" +%zu", frames.size() - k);
            break;
        }
        s += next;
    }
    return s;
}

// The percentage shown: whole percents rounded down, and 100 only when everything is done.
int percent(double fraction, bool finished)
{
    int p = int(std::floor(std::max(0.0, fraction) * 100));
    return finished ? 100 : std::min(p, 99);
}

} // namespace

Report::Report(double interval, bool quiet)
    : tty_(isatty(2) != 0), quiet_(quiet), interval_(interval)
{
    // A terminal shows the display at once; plain lines start after one interval (a line at
    // 0:00 says nothing).
    last_ = tty_ ? -1e9 : 0;
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

int Report::terminal_columns()
{
    const char *env = getenv("COLUMNS");
    if (env && atoi(env) > 0)
        return atoi(env);
    struct winsize ws;
    if (ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0)
        return ws.ws_col;
    return 80;
}

namespace {

int terminal_rows()
{
    const char *env = getenv("LINES");
    if (env && atoi(env) > 0)
        return atoi(env);
    struct winsize ws;
    if (ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_row > 0)
        return ws.ws_row;
    return 24;
}

} // namespace

std::vector<std::string> Report::display(const ProgressState &p, int columns, int rows)
{
    bool finished = p.frames_done >= p.frames_todo;
    int pc = percent(p.fraction, finished);
    std::string tail = strf(" %3d%%  %d/%d frames", pc, p.frames_done, p.frames_todo);
    if (p.resumed)
        tail += strf(" (+%d there)", p.resumed);
    tail += "  " + duration(p.elapsed) + "  ETA " + duration(p.eta);
    // The bar takes what the words leave, 10 to 30 columns.
    int bar = std::min(30, std::max(10, columns - 1 - 2 - int(tail.size())));
    int filled = int(p.fraction * bar);
    if (!finished)
        filled = std::min(filled, bar - 1);
    std::string line = "[" + std::string(size_t(std::max(0, filled)), '#') +
                       std::string(size_t(bar - std::max(0, filled)), '.') + "]" + tail;
    std::vector<std::string> out = {fit(line, columns)};
    std::string flight = strf("%d/%d slaves busy, in flight: ", p.busy, p.slaves);
    size_t room = size_t(std::max(8, columns - 1 - int(flight.size()) - 6));
    out.push_back(fit(flight + (p.in_flight.empty() ? "-" : frame_list(p.in_flight, room)),
                      columns));
    // One line per host, as many as the terminal has room for.
    int room_hosts = std::max(0, std::min(rows - 3, 8));
    int shown = 0;
    for (const HostProgress &h : p.hosts) {
        if (shown == room_hosts) {
            out.push_back(fit(strf("  ... %zu more host(s)", p.hosts.size() - size_t(shown)),
                              columns));
            break;
        }
        double pps = p.elapsed > 0 ? h.pixels / p.elapsed : 0;
        out.push_back(fit(strf("  %-16s %2d slave(s) %2d busy  ", h.name.c_str(), h.slaves,
                               std::min(h.busy, h.slaves)) + rate(pps, p.frame_pixels),
                          columns));
        shown++;
    }
    return out;
}

std::string Report::plain_line(const ProgressState &p)
{
    bool finished = p.frames_done >= p.frames_todo;
    std::string s = strf("fc-master: %d/%d frames (%d%%)", p.frames_done, p.frames_todo,
                         percent(p.fraction, finished));
    if (p.resumed)
        s += strf(", %d already there", p.resumed);
    s += strf(", %zu in flight, %d/%d slaves busy, %s elapsed, ETA %s", p.in_flight.size(), p.busy,
              p.slaves, duration(p.elapsed).c_str(), duration(p.eta).c_str());
    double pixels = 0;
    for (const HostProgress &h : p.hosts)
        pixels += h.pixels;
    if (p.elapsed > 0 && pixels > 0)
        s += ", " + rate(pixels / p.elapsed, p.frame_pixels);
    return s + "\n";
}

void Report::progress(const ProgressState &p)
{
    if (quiet_)
        return;
    double every = tty_ ? 0.25 : interval_;
    if (every <= 0 || p.elapsed - last_ < every)
        return;
    last_ = p.elapsed;
    if (!tty_) {
        fputs(plain_line(p).c_str(), stderr);
        fflush(stderr);
        return;
    }
    std::vector<std::string> lines = display(p, terminal_columns(), terminal_rows());
    // Back to the first line of the last display, then each line rewritten and cleared to
    // its end (a shorter line leaves nothing of the longer one behind).
    std::string out = "\r";
    if (lines_open_ > 1)
        out += strf("\033[%dA", lines_open_ - 1);
    for (size_t k = 0; k < lines.size(); k++)
        out += lines[k] + "\033[K" + (k + 1 < lines.size() ? "\n" : "");
    // A display with fewer lines than the last: clear the rest below.
    if (int(lines.size()) < lines_open_)
        out += "\033[J";
    fputs(out.c_str(), stderr);
    fflush(stderr);
    lines_open_ = int(lines.size());
}

void Report::clear_line()
{
    if (lines_open_ == 0)
        return;
    std::string out = "\r";
    if (lines_open_ > 1)
        out += strf("\033[%dA", lines_open_ - 1);
    out += "\033[J";
    fputs(out.c_str(), stderr);
    fflush(stderr);
    lines_open_ = 0;
}

namespace {

// Text cut into lines of at most kSummaryColumns - 1 columns at spaces; lines after the first
// are indented by `indent` spaces.
std::string wrapped(const std::string &text, size_t indent)
{
    const size_t room = size_t(Report::kSummaryColumns - 1);
    size_t pos = std::min(text.size(), text.find_first_not_of(' '));
    std::string out, line = text.substr(0, pos);
    bool first_word = true;     // of the line
    while (pos < text.size()) {
        size_t end = std::min(text.size(), text.find(' ', pos));
        std::string word = text.substr(pos, end - pos);
        pos = end + 1;
        if (word.empty())
            continue;
        if (!first_word && line.size() + 1 + word.size() > room) {
            out += line + "\n";
            line = std::string(indent, ' ');
            first_word = true;
        }
        line += (first_word ? "" : " ") + word;
        first_word = false;
    }
    return out + line + "\n";
}

// Seconds with the digits that matter.
std::string seconds(double s)
{
    return s < 10 ? strf("%.2f s", s) : s < 100 ? strf("%.1f s", s) : strf("%.0f s", s);
}

} // namespace

std::string Report::summary(const RunSummary &r) const
{
    std::string head;
    if (r.ok) {
        head = strf("fc-master: %d frame(s) rendered", r.rendered);
        if (r.resumed)
            head += strf(", %d already present", r.resumed);
        if (r.skipped)
            head += strf(", %d skipped by Pre_Frame_Command", r.skipped);
    } else if (!r.given_up.empty() && r.error.empty()) {
        head = strf("fc-master: %d frame(s) rendered, %d already present, %zu failed", r.rendered,
                    r.resumed, r.given_up.size());
    } else {
        head = strf("fc-master: %s with %d of %d frame(s) done (%d rendered, %d already "
                    "present), %d missing", r.error.empty() ? "stopped" : "failed",
                    r.rendered + r.resumed, r.total, r.rendered, r.resumed,
                    r.total - r.rendered - r.resumed - r.skipped);
    }
    head += strf(" in %s, %s division, %zu host(s) of a %s virtual machine",
                 duration(r.elapsed).c_str(), r.division.c_str(), r.hosts.size(),
                 r.virtual_machine.c_str());
    std::string s = wrapped(head, 2);
    if (!r.given_up.empty()) {
        std::string list;
        for (auto &f : r.given_up)
            list += (list.empty() ? "" : ", ") + std::to_string(f.first);
        s += wrapped(strf("  frames without a file (their messages above): %s", list.c_str()), 4);
    }
    if (!r.frame_seconds.empty()) {
        std::vector<double> sorted = r.frame_seconds;
        std::sort(sorted.begin(), sorted.end());
        size_t slowest = size_t(std::max_element(r.frame_seconds.begin(), r.frame_seconds.end()) -
                                r.frame_seconds.begin());
        s += wrapped(strf("  frame time: median %s, fastest %s, slowest %s (frame %d); parse and "
                          "trace, all its jobs", seconds(sorted[sorted.size() / 2]).c_str(),
                          seconds(sorted.front()).c_str(), seconds(sorted.back()).c_str(),
                          r.frame_numbers[slowest]), 4);
    }
    if (r.retried || r.lost)
        s += wrapped(strf("  %d frame(s) retried after a failed or lost job, %d lost", r.retried,
                          r.lost), 4);
    if (r.savings.known && r.savings.rays_full > 0) {
        const Savings &v = r.savings;
        double rays = std::max(0.0, v.rays_full - v.rays_spent);
        s += wrapped(strf("  frame coherence saved about %.0f%% of the rays: %.3g of %.3g million "
                          "traced (estimated from each renderer's first frame, traced in full); "
                          "trace time %.1f s, %.1f s at the first frames' rate (an upper bound: "
                          "a first frame also records every ray)",
                          100 * rays / v.rays_full, v.rays_spent / 1e6, v.rays_full / 1e6,
                          v.seconds_spent, v.seconds_full), 4);
    }
    // The host table, 79 columns: a longer host name gets a line of its own.
    const char *row = "  %-16s %6s %5s %6s %6s %11s %8s %12s\n";
    s += strf(row, "host", "slaves", "jobs", "frames", "tiles", "rays", "busy", "throughput");
    for (auto &kv : r.hosts) {
        const HostStat &h = kv.second;
        double pps = r.elapsed > 0 ? h.pixels / r.elapsed : 0;
        std::string tput = pps >= 1e6 ? strf("%.1f Mpx/s", pps / 1e6) : strf("%.0f kpx/s", pps / 1e3);
        std::string name = h.name;
        if (name.size() > 16) {
            s += "  " + name + "\n";
            name.clear();
        }
        std::string rays = h.rays < 1e10 ? strf("%.0f", h.rays) : strf("%.3g", h.rays);
        s += strf(row, name.c_str(), std::to_string(h.slaves).c_str(),
                  std::to_string(h.jobs).c_str(), std::to_string(h.frames).c_str(),
                  std::to_string(h.tiles).c_str(), rays.c_str(), duration(h.busy).c_str(),
                  tput.c_str());
        if (h.excluded)
            s += "    (left out after failures)\n";
    }
    return s;
}

} // namespace fc
