// shellout.cpp - Pre/Post_Scene and Pre/Post_Frame commands on the master (see shellout.h).
#include "shellout.h"

#include <sys/wait.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "povray.h"
#include "util.h"

namespace fc {

namespace {

const char *const kEventKeys[Shellouts::kEvents] = {"Pre_Scene", "Pre_Frame", "Post_Frame",
                                                    "Post_Scene"};
const char *const kEventNames[Shellouts::kEvents] = {"pre-scene", "pre-frame", "post-frame",
                                                     "post-scene"};

// An INI value as POV-Ray writes it: maybe in double quotes.
std::string ini_value(const std::string &v)
{
    std::string t = trim(v);
    if (t.size() >= 2 && t.front() == '"' && t.back() == '"')
        return t.substr(1, t.size() - 2);
    return t;
}

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
    bool ok = status == 0;
    if (c.negate)
        ok = !ok;
    if (ok || c.action == 'i')
        return r;
    std::string program, params;
    split_command(c.command, program, params);
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

bool probe_shellouts(const std::string &renderer, const std::vector<std::string> &options,
                     const std::string &cwd, const std::string &tmpdir, double timeout,
                     Shellouts &out, std::string &err)
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
        err = renderer + " wrote no resolved options (Create_Ini); is it povray-fc with the "
                         "frame channel (patch 0020)?";
        return false;
    }
    double final_clock = 1, initial_clock = 0;
    int initial_frame = 1, final_frame = 1;
    bool cyclic = false;
    std::string line;
    while (std::getline(in, line)) {
        size_t eq = line.find('=');
        if (eq == std::string::npos)
            continue;
        std::string key = trim(line.substr(0, eq)), value = ini_value(line.substr(eq + 1));
        for (int e = 0; e < Shellouts::kEvents; e++) {
            if (key == std::string(kEventKeys[e]) + "_Command") {
                out.commands[e].command = value;
            } else if (key == std::string(kEventKeys[e]) + "_Return" && !value.empty()) {
                size_t k = (value[0] == '-' || value[0] == '!') ? 1 : 0;
                out.commands[e].negate = k == 1;
                if (k < value.size())
                    out.commands[e].action = char(tolower((unsigned char)value[k]));
            }
        }
        if (key == "Initial_Clock") initial_clock = atof(value.c_str());
        else if (key == "Final_Clock") final_clock = atof(value.c_str());
        else if (key == "Initial_Frame") initial_frame = atoi(value.c_str());
        else if (key == "Final_Frame") final_frame = atoi(value.c_str());
        else if (key == "Cyclic_Animation") cyclic = value == "On" || value == "on";
        else if (key == "Input_File_Name") out.scene = base_name(value);
    }
    // AnimationProcessing's clock: a cyclic animation's final frame is one past the last.
    int span = final_frame + (cyclic ? 1 : 0) - initial_frame;
    out.initial_frame = initial_frame;
    out.initial_clock = initial_clock;
    out.clock_delta = span != 0 ? (final_clock - initial_clock) / double(span) : 0;
    return true;
}

} // namespace fc
