// povray_probe.cpp - asking POV-Ray for the resolved options, and its output names (see
// povray_probe.h).
#include "povray_probe.h"

#include <poll.h>
#include <unistd.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "child_process.h"
#include "clock.h"
#include "files.h"
#include "povray_console.h"
#include "text.h"
#include "watchdog.h"

namespace fc {

const char *const kFrameCoherenceOption = "Frame_Coherence=on";

bool run_collect(const std::vector<std::string> &argv, const std::string &cwd, double timeout,
                 std::vector<std::string> &lines, int &status, std::string &err)
{
    Child child;
    if (!start_child(argv, cwd, 0, child, err))
        return false;
    double deadline = now() + timeout;
    while (child.fd >= 0) {
        struct pollfd p = {child.fd, POLLIN, 0};
        int left = int((deadline - now()) * 1000);
        if (left <= 0) {
            kill_child(child);
            err = strf("%s did not finish within %.0f s", argv[0].c_str(), timeout);
            return false;
        }
        poll(&p, 1, std::min(left, 100));
        read_child(child, lines);
        if (int sig = watchdog::stop_requested()) {
            kill_child(child);
            err = strf("interrupted (%s)", strsignal(sig));
            return false;
        }
    }
    if (!wait_child(child, std::max(1.0, deadline - now()), status)) {
        kill_child(child);
        err = strf("%s did not exit within %.0f s", argv[0].c_str(), timeout);
        return false;
    }
    return true;
}

namespace {

// Join POV-Ray's 80-column wrapped physical lines starting at index i until `until` appears.
std::string join_until(const std::vector<std::string> &lines, size_t i, const char *until)
{
    std::string s;
    for (size_t k = i; k < lines.size() && k < i + 20; k++) {
        s += lines[k];
        if (s.find(until) != std::string::npos)
            break;
    }
    return s;
}

} // namespace

int frame_digits(int final_frame, bool cyclic)
{
    int f = final_frame + (cyclic ? 1 : 0);
    int digits = 1;
    for (int i = f; i >= 10; i /= 10)
        digits++;
    return digits;
}

std::string frame_file_name(const std::string &stem, int digits, int frame, const std::string &ext)
{
    if (digits <= 0)
        return stem + ext;
    return stem + strf("%0*d", digits, frame) + ext;
}

bool find_bad_option(const std::string &renderer, const std::vector<std::string> &options,
                     const std::string &cwd, double timeout, std::string &err)
{
    // A file named on the command line (an INI file or the scene) that is not there.
    for (const std::string &o : options) {
        if (o.empty() || o[0] == '+' || o[0] == '-' || o.find('=') != std::string::npos)
            continue;
        std::string path = o[0] == '/' ? o : cwd + "/" + o;
        if (access(path.c_str(), R_OK) != 0) {
            err = strf("%s: %s (an INI file or scene named on the command line)", o.c_str(),
                       strerror(errno));
            return true;
        }
    }
    // A switch POV-Ray cannot take: tried alone, it fails the same way (-D: no display).
    for (const std::string &o : options) {
        if (o.empty() || (o[0] != '+' && o[0] != '-'))
            continue;
        std::vector<std::string> lines;
        int status = 0;
        std::string ignored;
        if (!run_collect({renderer, "-D", o, "-I/dev/null/none"}, cwd, timeout, lines, status,
                         ignored))
            continue;
        for (const std::string &l : lines)
            if (l.find("Failed to parse command-line option") != std::string::npos) {
                err = "POV-Ray does not take the option " + o +
                      " (\"Failed to parse command-line option\")";
                return true;
            }
    }
    return false;
}

bool probe_scene(const std::string &renderer, const std::vector<std::string> &options,
                 const std::string &cwd, const std::string &tmpdir, double timeout,
                 SceneInfo &info, std::string &err)
{
    std::string inc = tmpdir + "/fc-probe.inc";
    if (!write_text(inc, strf("#error \"%s\"\n", kProbeMarker), err))
        return false;
    std::vector<std::string> argv = {renderer};
    argv.insert(argv.end(), options.begin(), options.end());
    argv.insert(argv.end(), {"-D", "-UA", "+HI" + inc});
    for (const char *cmd : kShelloutOptions)
        argv.push_back(std::string(cmd) + "=");
    argv.push_back(std::string("Pre_Scene_Command=") + kProbeShellout);
    argv.push_back("Pre_Scene_Return=i");
    std::vector<std::string> lines;
    int status = 0;
    if (!run_collect(argv, cwd, timeout, lines, status, err))
        return false;
    // POV-Ray says so when povray.conf forbids shell-outs.
    info.shellouts_permitted = true;
    for (const std::string &l : lines)
        if (l.find(std::string("shellout '") + kProbeShellout + "' prohibited") != std::string::npos)
            info.shellouts_permitted = false;

    bool marker = false, have_res = false, have_out = false;
    for (size_t i = 0; i < lines.size(); i++) {
        const std::string &l = lines[i];
        int a, b, c, d, e, f;
        char on[8];
        if (info.banner.empty() && l.find("Ray Tracer Version") != std::string::npos)
            info.banner = trim(l);
        if (l.find(kProbeMarker) != std::string::npos)
            marker = true;
        else if (sscanf(l.c_str(), " Initial Frame: %d Final Frame: %d", &a, &b) == 2)
            info.initial_frame = a, info.final_frame = b, info.animated = true;
        else if (sscanf(l.c_str(), " Frame Step: %d", &a) == 1)
            info.frame_step = std::max(1, a);
        else if (sscanf(l.c_str(), " Cyclic Animation.....%7s", on) == 1)
            info.cyclic = strncmp(on, "On", 2) == 0;
        else if (sscanf(l.c_str(), " Image resolution.....%d by %d (rows %d to %d, columns %d to %d",
                        &a, &b, &c, &d, &e, &f) == 6) {
            info.width = a, info.height = b;
            info.area = Rect{e - 1, c - 1, f, d};
            have_res = true;
        } else if (starts_with(trim(l), "Output file..........")) {
            // "Output file..........NAME, 24 bpp Targa", wrapped at 80 columns.
            std::string joined = join_until(lines, i, " bpp");
            size_t start = joined.find("Output file..........") + strlen("Output file..........");
            size_t end = joined.rfind(", ");
            if (end != std::string::npos && end > start) {
                info.output_name = joined.substr(start, end - start);
                have_out = true;
            }
        }
    }
    if (!marker || !have_res || !have_out) {
        std::string excerpt = failure_excerpt(lines);
        // POV-Ray does not say which option it could not take: find it.
        if (excerpt.find("Failed to parse command-line option") != std::string::npos &&
            find_bad_option(renderer, options, cwd, timeout, err))
            return false;
        err = strf("%s rejected the scene or its options (%s):\n%s", renderer.c_str(),
                  describe_status(status).c_str(), excerpt.c_str());
        return false;
    }
    if (info.width <= 0 || info.height <= 0 || info.area.width() <= 0 || info.area.height() <= 0 ||
        info.area.x0 < 0 || info.area.y0 < 0 || info.area.x1 > info.width ||
        info.area.y1 > info.height) {
        err = strf("%s reported an unusable image size %dx%d", renderer.c_str(), info.width,
                  info.height);
        return false;
    }
    return true;
}

bool split_output_name(SceneInfo &info, const std::string &ext, std::string &err)
{
    // POV-Ray printed the first frame's name: strip the extension and the padded frame number.
    std::string name = info.output_name;
    if (name.size() < ext.size() || name.compare(name.size() - ext.size(), ext.size(), ext) != 0) {
        err = "unexpected output file name from POV-Ray: " + name + " (expected " + ext + ")";
        return false;
    }
    name.resize(name.size() - ext.size());
    info.ext = ext;
    info.frames.clear();
    if (info.animated) {
        info.digits = frame_digits(info.final_frame, info.cyclic);
        // The first frame's number ends the name (the frames themselves come from set_frames).
        size_t nd = 0;
        while (nd < name.size() && isdigit((unsigned char)name[name.size() - 1 - nd]))
            nd++;
        if (nd < size_t(info.digits)) {
            err = "cannot find the frame number in POV-Ray's output name " + info.output_name;
            return false;
        }
        info.stem = name.substr(0, name.size() - size_t(info.digits));
    } else {
        info.digits = 0;
        info.stem = name;
        info.frames.push_back(0);
    }
    return true;
}

namespace {

std::string ini_value(const std::string &v)
{
    std::string t = trim(v);
    if (t.size() >= 2 && t.front() == '"' && t.back() == '"')
        return t.substr(1, t.size() - 2);
    return t;
}

} // namespace

std::string resolved_value(const ResolvedOptions &ini, const char *key, const char *fallback)
{
    auto it = ini.find(key);
    return it == ini.end() ? fallback : it->second;
}

bool option_is_on(const std::string &value)
{
    std::string s;
    for (char c : value)
        s += char(tolower((unsigned char)c));
    return s == "on" || s == "true" || s == "yes" || s == "1";
}

bool probe_resolved_options(const std::string &renderer, const std::vector<std::string> &options,
                            const std::string &cwd, const std::string &tmpdir, double timeout,
                            ResolvedOptions &out, std::string &err)
{
    std::string ini = tmpdir + "/resolved.ini";
    std::vector<std::string> argv = {renderer};
    argv.insert(argv.end(), options.begin(), options.end());
    argv.push_back("+GI" + ini);
    argv.push_back("Frame_Channel=" + tmpdir + "/no-such-directory/channel");
    std::vector<std::string> lines;
    int status = 0;
    if (!run_collect(argv, cwd, timeout, lines, status, err))
        return false;
    std::ifstream in(ini);
    if (!in) {
        // Its exit and last line say why (a povray-fc without the frame channel, or a failure of
        // its own: seen once in CI, unexplained).
        std::string last;
        for (auto it = lines.rbegin(); it != lines.rend() && last.empty(); ++it)
            last = trim(*it);
        err = renderer + " wrote no resolved options (Create_Ini; " + describe_status(status) +
              (last.empty() ? std::string(", no output") : ", last line: " + last) +
              "); fc-master needs povray-fc with the frame channel";
        return false;
    }
    std::string line;
    while (std::getline(in, line)) {
        size_t eq = line.find('=');
        if (eq != std::string::npos && line[0] != ';')
            out[trim(line.substr(0, eq))] = ini_value(line.substr(eq + 1));
    }
    return true;
}

bool set_frames(SceneInfo &info, const ResolvedOptions &ini, std::string &err)
{
    if (!info.animated)
        return true;
    auto get = [&](const char *key, double fallback) {
        auto it = ini.find(key);
        return it == ini.end() ? fallback : atof(it->second.c_str());
    };
    auto cyc = ini.find("Cyclic_Animation");
    bool cyclic = cyc != ini.end() && (cyc->second == "On" || cyc->second == "on");
    // AnimationProcessing's arithmetic: a cyclic animation's final frame is one past the
    // last; a subset bound in (0, 1) is a fraction of the animation.
    int initial = std::max(int(get("Initial_Frame", 1)), 0);
    int final = std::max(int(get("Final_Frame", 1)), initial) + (cyclic ? 1 : 0);
    // The first frame too, not the number in the console's first output name: one newton-table
    // run on a loaded machine started at frame 2 and rendered 44 of 45 frames as a success.
    int start = initial;
    if (ini.count("Subset_Start_Frame")) {
        float p = std::max(float(get("Subset_Start_Frame", 0)), 0.0f);
        start = std::max((p == 0 || p >= 1) ? int(p) : int(float(final - initial + 1) * p), initial);
    }
    info.first_frame = start;
    int end = final - (cyclic ? 1 : 0);
    if (ini.count("Subset_End_Frame")) {
        float p = std::max(float(get("Subset_End_Frame", 0)), 0.0f);
        end = (p == 0 || p >= 1) ? int(p) : int(float(final - initial + 1) * p);
        end = std::max(end, info.first_frame);
    }
    info.frames.clear();
    for (int f = info.first_frame; f <= end; f += info.frame_step)
        info.frames.push_back(f);
    if (info.frames.empty()) {
        err = "no frames to render";
        return false;
    }
    return true;
}

} // namespace fc
