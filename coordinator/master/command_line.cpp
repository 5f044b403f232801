// command_line.cpp - fc-master's command line (see command_line.h).
#include "command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>

#include "text.h"
#include "virtual_machine.h"

namespace fc {

namespace {

const char *const kUsage =
    "usage: fc-master [OPTIONS] SCENE.pov|SCENE.ini [POVRAY-OPTIONS...] -o DIR";

const char *const kHelp =
    "Render a POV-Ray animation on the hosts of a PVM virtual machine.\n"
    "\n"
    "POV-Ray options and INI files pass through unchanged (+W320 +H240 +KFI1 +KFF45 ...).\n"
    "Frames are written to DIR under the names and in the format one povray-fc process\n"
    "writes with the same options (its povray.ini included). Frames already complete in DIR\n"
    "are not rendered again unless a file they read changed; after other options or another\n"
    "renderer, fc-master stops and says what changed (then --force).\n"
    "\n"
    "Options:\n"
    "  -o, --output DIR        output directory (default: where POV-Ray would write)\n"
    "  --division MODE         sequence | frame | hybrid (default frame)\n"
    "  --tile N                tile size in pixels for frame/hybrid division (default 64)\n"
    "  --ranges N              initial frame ranges: sequence (default: one per slave),\n"
    "                          hybrid (default: one per two slaves)\n"
    "  --slaves N              slaves per host, each renderer using cores/N threads\n"
    "                          (default: one with frame coherence, one per core with --no-fc)\n"
    "  --hostfile FILE         pvmd host file: its hosts are added to the virtual machine\n"
    "                          (each must be added, or nothing renders)\n"
    "  --pvmd-name NAME        host name of a private pvmd (-nNAME; needed to add hosts\n"
    "                          when this host's name resolves to a loopback address)\n"
    "  --private               always start a private pvmd, even if one runs\n"
    "  --no-fc                 render without frame coherence\n"
    "  --no-duplicates         idle slaves never duplicate running work (stragglers)\n"
    "  --keep-going            render every frame that can be rendered: a frame that fails\n"
    "                          (a scene error, or failing or hanging on two hosts) is listed\n"
    "                          at the end instead of stopping the render (exit status 1)\n"
    "  --no-local-slaves       no slaves on the master's own host (it only assembles, as\n"
    "                          in the paper; e.g. to emulate a cluster of namespace hosts)\n"
    "  --povray PATH           renderer, povray-fc (default: next to fc-master, then PATH)\n"
    "  --slave PATH            fc-slave binary (default: next to fc-master)\n"
    "  --timeout SECONDS       a slave silent this long since it was given work is presumed\n"
    "                          dead (default 120); also a job's deadline until one finished\n"
    "  --nice N                run the renderer with this nice increment (default 0)\n"
    "  --progress SECONDS      interval of progress lines when stderr is no terminal (10)\n"
    "  --quiet                 no progress output\n"
    "  --force                 render every frame again, even if DIR holds frames of another\n"
    "                          scene or options (each is replaced when its new one is complete)\n"
    "  --no-preview            no DIR/preview/latest.png and contact-sheet.png\n"
    "  --stats FILE            write per-frame and per-job statistics as JSON\n"
    "  --help                  show this help\n";

// A usage error: the parse stops at the first.
struct UsageError {
    std::string message;
};

[[noreturn]] void usage_error(const std::string &msg)
{
    throw UsageError{msg};
}

bool parse_int(const std::string &s, int lo, int hi, int &v)
{
    char *end = nullptr;
    errno = 0;
    long x = strtol(s.c_str(), &end, 10);
    if (s.empty() || *end || errno || x < lo || x > hi)
        return false;
    v = int(x);
    return true;
}

bool parse_seconds(const std::string &s, double &v)
{
    char *end = nullptr;
    double x = strtod(s.c_str(), &end);
    if (s.empty() || *end || !(x > 0) || !std::isfinite(x))
        return false;
    v = x;
    return true;
}

} // namespace

namespace {

void set_output(Options &o, const std::string &option, const std::string &dir)
{
    // A second -o would take the scene for a directory and leave no scene.
    if (!o.output.empty())
        usage_error(option + " given twice (" + o.output + ", then " + dir + ")");
    o.output = dir;
}

void parse(const std::vector<std::string> &args, Options &o, bool &help)
{
    size_t argc = args.size();
    for (size_t i = 0; i < argc; i++) {
        std::string a = args[i];
        if (a == "--help") {
            help = true;
            return;
        }
        if (a == "-o") {
            if (i + 1 >= argc)
                usage_error("-o needs a directory");
            set_output(o, "-o", args[++i]);
            continue;
        }
        if (!starts_with(a, "--")) {
            o.pov.push_back(a);     // POV-Ray option, INI file or scene
            continue;
        }
        std::string name = a, value;
        bool has_value = false;
        size_t eq = a.find('=');
        if (eq != std::string::npos) {
            name = a.substr(0, eq);
            value = a.substr(eq + 1);
            has_value = true;
        }
        static const std::set<std::string> flags = {"--private", "--no-fc", "--no-duplicates",
                                                    "--no-local-slaves", "--quiet", "--force",
                                                    "--no-preview", "--keep-going"};
        static const std::set<std::string> valued = {
            "--output", "--division", "--tile", "--ranges", "--slaves", "--hostfile", "--pvmd-name",
            "--povray", "--slave", "--timeout", "--nice", "--progress", "--stats"};
        if (flags.count(name)) {
            if (has_value)
                usage_error("option " + name + " takes no value");
            if (name == "--private") o.force_private = true;
            else if (name == "--no-fc") o.fc = false;
            else if (name == "--no-duplicates") o.duplicates = false;
            else if (name == "--no-local-slaves") o.local_slaves = false;
            else if (name == "--quiet") o.quiet = true;
            else if (name == "--force") o.force = true;
            else if (name == "--no-preview") o.preview = false;
            else if (name == "--keep-going") o.keep_going = true;
            continue;
        }
        if (!valued.count(name))
            usage_error("unknown option " + name);
        if (!has_value) {
            if (i + 1 >= argc)
                usage_error("option " + name + " needs a value");
            value = args[++i];
        }
        if (name == "--output") {
            set_output(o, "--output", value);
        } else if (name == "--division") {
            if (!parse_division(value, o.division))
                usage_error("--division must be sequence, frame or hybrid, not '" + value + "'");
        } else if (name == "--tile") {
            if (!parse_int(value, 8, 100000, o.tile))
                usage_error("--tile must be a whole number of pixels >= 8, not '" + value + "'");
        } else if (name == "--ranges") {
            if (!parse_int(value, 1, 1000000, o.ranges))
                usage_error("--ranges must be a whole number >= 1, not '" + value + "'");
        } else if (name == "--slaves") {
            if (!parse_int(value, 1, 1024, o.slaves))
                usage_error("--slaves must be a whole number from 1 to 1024, not '" + value + "'");
        } else if (name == "--hostfile") {
            // A host file that cannot be read is a mistake on the command line, not a reason
            // to render on this host alone.
            FILE *f = fopen(value.c_str(), "r");
            if (!f)
                usage_error("--hostfile " + value + ": " + strerror(errno));
            char probe;
            bool readable = fread(&probe, 1, 1, f) == 1 || !ferror(f);
            int e = errno;
            fclose(f);
            if (!readable)
                usage_error("--hostfile " + value + ": " + strerror(e));
            // Nor is a host file without hosts (all comments, or empty).
            if (hostfile_hosts(value).empty())
                usage_error("--hostfile " + value + " names no host");
            o.hostfile = value;
        } else if (name == "--pvmd-name") {
            o.pvmd_name = value;
        } else if (name == "--povray") {
            o.povray = value;
        } else if (name == "--slave") {
            o.slave = value;
        } else if (name == "--timeout") {
            if (!parse_seconds(value, o.timeout))
                usage_error("--timeout must be a positive number of seconds, not '" + value + "'");
        } else if (name == "--nice") {
            if (!parse_int(value, 0, 19, o.nice))
                usage_error("--nice must be from 0 to 19, not '" + value + "'");
        } else if (name == "--progress") {
            if (!parse_seconds(value, o.progress))
                usage_error("--progress must be a positive number of seconds, not '" + value + "'");
        } else if (name == "--stats") {
            o.stats = value;
        }
    }
    if (o.pov.empty())
        usage_error("no scene given");
    // With frame coherence one slave per host, its renderer on every core: a renderer's
    // first frame is traced in full and each renderer parses every frame it has tiles of, so
    // a slave per core pays both once per core (sequence division on 2 cores: 1.08 against
    // 1.04 of one process, Newton 640x480, 45 frames). Without fc, one per core: their
    // parses then overlap the others' tracing.
    if (o.slaves == 0 && o.fc)
        o.slaves = 1;
}

} // namespace

bool parse_command_line(const std::vector<std::string> &args, Options &o, bool &help,
                        std::string &err)
{
    o = Options();
    help = false;
    try {
        parse(args, o, help);
    } catch (const UsageError &e) {
        err = e.message;
        return false;
    }
    return true;
}

Options parse_options(int argc, char **argv)
{
    Options o;
    bool help = false;
    std::string err;
    if (!parse_command_line(std::vector<std::string>(argv + 1, argv + argc), o, help, err)) {
        fprintf(stderr, "fc-master: %s\n%s\nTry 'fc-master --help' for more information.\n",
                err.c_str(), kUsage);
        exit(2);
    }
    if (help) {
        printf("%s\n\n%s", kUsage, kHelp);
        exit(0);
    }
    return o;
}


} // namespace fc
