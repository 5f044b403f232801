// shellout.cpp - Pre/Post_Scene and Pre/Post_Frame commands on the master (see shellout.h).
#include "shellout.h"

#include <sys/wait.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "debug_log.h"
#include "files.h"
#include "povray_probe.h"
#include "text.h"

namespace fc {

namespace {

const char *const kEventKeys[Shellouts::kEvents] = {"Pre_Scene", "Pre_Frame", "Post_Frame",
                                                    "Post_Scene"};
const char *const kEventNames[Shellouts::kEvents] = {"pre-scene", "pre-frame", "post-frame",
                                                     "post-scene"};

// Split "program params" at the first space outside quotes (POV-Ray's ExtractCommand).
void split_command(const std::string &raw, std::string &program, std::string &params)
{
    std::string s = trim(raw);
    bool sq = false, dq = false;
    size_t i = 0;
    for (; i < s.size(); i++) {
        char c = s[i];
        if (c == '\'' && !dq) sq = !sq;
        else if (c == '"' && !sq) dq = !dq;
        else if (isspace((unsigned char)c) && !sq && !dq) break;
    }
    program = s.substr(0, i);
    params = i < s.size() ? trim(s.substr(i)) : "";
}

} // namespace

bool Shellouts::any() const
{
    for (const Command &c : commands)
        if (!c.command.empty())
            return true;
    return false;
}

std::string Shellouts::expand(const std::string &raw, int frame, const std::string &output) const
{
    std::string program, params, out;
    split_command(raw, program, params);
    double clock = double(float(clock_delta * double(frame - initial_frame) + initial_clock));
    for (size_t i = 0; i < params.size(); i++) {
        if (params[i] != '%' || i + 1 >= params.size()) {
            out += params[i];
            continue;
        }
        char c = params[++i];
        switch (c) {
        case '%': out += "%%"; break;      // POV-Ray keeps both
        case 'o': out += output; break;
        case 's': out += scene; break;
        case 'n': out += strf("%u", unsigned(frame)); break;
        case 'k': out += strf("%#.6f", clock); break;
        case 'h': out += strf("%u", unsigned(height)); break;
        case 'w': out += strf("%u", unsigned(width)); break;
        default: out += '%'; out += c; break;
        }
    }
    return trim(program + " " + out);
}

ShelloutResult Shellouts::run(Event event, int frame, const std::string &output) const
{
    ShelloutResult r;
    const Command &c = commands[event];
    if (c.command.empty())
        return r;
    std::string cmd = expand(c.command, frame, output);
    int status = 1;     // a forbidden command counts as failed, as in POV-Ray
    if (permitted) {
        debug_log("%s shell-out: %s", kEventNames[event], cmd.c_str());
        int w = system(cmd.c_str());
        status = w == -1 ? -1 : (WIFEXITED(w) ? WEXITSTATUS(w) : 1);
    }
    std::string program, params;
    split_command(c.command, program, params);
    if (!permitted && !told[event]) {
        // POV-Ray's own line, once per command rather than once per frame.
        told[event] = true;
        r.notice = "Execution of shellout '" + program + "' prohibited (povray.conf's "
                   "[Shellout Security])";
    }
    bool ok = status == 0;
    if (c.negate)
        ok = !ok;
    if (ok || c.action == 'i')
        return r;
    std::string why = strf("the %s shell-out ('%s'%s) ", kEventNames[event], program.c_str(),
                           permitted ? "" : ", prohibited by povray.conf");
    switch (c.action) {
    case 'q':
        r.action = ShelloutResult::Quit;
        r.message = "render halted because " + why + "requested to quit rendering";
        break;
    case 'u':
    case 'f':
        r.action = ShelloutResult::Fatal;
        r.message = "render halted because " + why + "requested to " +
                    (c.action == 'u' ? "abort" : "generate a fatal error");
        break;
    case 's':
        r.action = ShelloutResult::SkipFrame;
        r.message = why + "requested to skip a frame";
        break;
    case 'a':
        r.action = ShelloutResult::SkipAll;
        r.message = why + "requested to skip all remaining frames";
        break;
    }
    return r;
}

void read_shellouts(const ResolvedOptions &ini, Shellouts &out)
{
    for (int e = 0; e < Shellouts::kEvents; e++) {
        auto c = ini.find(std::string(kEventKeys[e]) + "_Command");
        if (c != ini.end())
            out.commands[e].command = c->second;
        auto r = ini.find(std::string(kEventKeys[e]) + "_Return");
        if (r != ini.end() && !r->second.empty()) {
            const std::string &v = r->second;
            size_t k = (v[0] == '-' || v[0] == '!') ? 1 : 0;
            out.commands[e].negate = k == 1;
            if (k < v.size())
                out.commands[e].action = char(tolower((unsigned char)v[k]));
        }
    }
    auto num = [&](const char *key, double fallback) {
        auto it = ini.find(key);
        return it == ini.end() ? fallback : atof(it->second.c_str());
    };
    auto cyc = ini.find("Cyclic_Animation");
    bool cyclic = cyc != ini.end() && (cyc->second == "On" || cyc->second == "on");
    auto in = ini.find("Input_File_Name");
    if (in != ini.end())
        out.scene = base_name(in->second);
    // AnimationProcessing's clock: a cyclic animation's final frame is one past the last.
    int initial_frame = int(num("Initial_Frame", 1));
    int span = int(num("Final_Frame", 1)) + (cyclic ? 1 : 0) - initial_frame;
    out.initial_frame = initial_frame;
    out.initial_clock = num("Initial_Clock", 0);
    out.clock_delta = span != 0 ? (num("Final_Clock", 1) - out.initial_clock) / double(span) : 0;
}

} // namespace fc
