// command_line.h - fc-master's command line: our options, and POV-Ray's passed through.
#pragma once

#include <string>
#include <vector>

#include "schedule.h"

namespace fc {

struct Options {
    std::string output;
    Division division = Division::Frame;
    int tile = 64;              // a multiple of POV-Ray's 32-pixel render blocks
    int ranges = 0;             // 0 = the division's default
    int slaves = 0;             // 0 = one per core (only with --no-fc: fc's default is 1)
    std::string hostfile;
    std::string pvmd_name;
    bool force_private = false;
    bool fc = true;
    bool duplicates = true;
    bool keep_going = false;    // a frame that fails is listed at the end, the others render
    bool local_slaves = true;   // false: the master's own host renders nothing
    std::string povray;
    std::string slave;
    double timeout = 120;
    int nice = 0;
    double progress = 10;
    bool quiet = false;
    bool force = false;         // render every frame again, whatever the output directory holds
    bool preview = true;        // DIR/preview/latest.png and contact-sheet.png
    std::string stats;
    std::vector<std::string> pov;   // POV-Ray options, in order
};

// Parse the arguments (without the program's name) into o; help: --help was asked. False with
// err (one line naming the option) on a usage error.
bool parse_command_line(const std::vector<std::string> &args, Options &o, bool &help,
                        std::string &err);

// parse_command_line for main: prints the help and exits 0 for --help; prints the error with
// the usage and exits 2 for a bad option.
Options parse_options(int argc, char **argv);

} // namespace fc
