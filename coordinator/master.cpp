// master.cpp - fc-master: renders a POV-Ray animation on the hosts of a PVM virtual machine.
//
// Flow: parse our options (POV-Ray's pass through untouched), ask POV-Ray for the resolved
// image size, frames and output name (probe_scene), skip frames already complete in the
// output directory (resume), join or start a virtual machine, spawn fc-slave tasks, then run
// the one receive loop: receive any message, switch on its tag, each case a short handler.
// Slaves get their next work unit in the step that handles their FC_DONE. Every wait has a
// timeout; the loop also watches for silent slaves, signals and the end of the work.
#include <signal.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include <pvm3.h>

#include "frames.h"
#include "povray.h"
#include "protocol.h"
#include "pvmutil.h"
#include "report.h"
#include "schedule.h"
#include "util.h"

using namespace fc;

namespace {

volatile sig_atomic_t g_signal = 0;

void on_signal(int sig) { g_signal = sig; }

const char *const kUsage =
    "usage: fc-master [OPTIONS] SCENE.pov|SCENE.ini [POVRAY-OPTIONS...] -o DIR";

const char *const kHelp =
    "Render a POV-Ray animation on the hosts of a PVM virtual machine.\n"
    "\n"
    "POV-Ray options and INI files pass through unchanged (+W320 +H240 +KFI1 +KFF45 ...).\n"
    "Frames are written to DIR under POV-Ray's own names (24-bit Targa); frames already\n"
    "complete in DIR are not rendered again.\n"
    "\n"
    "Options:\n"
    "  -o, --output DIR        output directory (default: where POV-Ray would write)\n"
    "  --division MODE         sequence | frame | hybrid (default frame)\n"
    "  --tile N                tile size in pixels for frame/hybrid division (default 80)\n"
    "  --ranges N              initial frame ranges for sequence/hybrid (default: slaves)\n"
    "  --slaves N              slaves per host (default: one per core)\n"
    "  --hostfile FILE         pvmd host file for a private virtual machine\n"
    "  --pvmd-name NAME        host name of a private pvmd (-nNAME; needed to add hosts\n"
    "                          when this host's name resolves to a loopback address)\n"
    "  --private               always start a private pvmd, even if one runs\n"
    "  --no-fc                 render without frame coherence\n"
    "  --no-duplicates         idle slaves never duplicate running work (stragglers)\n"
    "  --no-local-slaves       no slaves on the master's own host (it only assembles, as\n"
    "                          in the paper; e.g. to emulate a cluster of namespace hosts)\n"
    "  --povray PATH           renderer (default: povray-fc next to fc-master, then PATH)\n"
    "  --slave PATH            fc-slave binary (default: next to fc-master)\n"
    "  --timeout SECONDS       a slave silent this long is presumed dead (default 120)\n"
    "  --nice N                run the renderer with this nice increment (default 0)\n"
    "  --progress SECONDS      interval of progress lines when stderr is no terminal (10)\n"
    "  --quiet                 no progress output\n"
    "  --stats FILE            write per-frame and per-unit statistics as JSON\n"
    "  --help                  show this help\n";

struct Options {
    std::string output;
    Division division = Division::Frame;
    int tile = 80;
    int ranges = 0;
    int slaves = 0;             // 0 = one per core
    std::string hostfile;
    std::string pvmd_name;
    bool force_private = false;
    bool fc = true;
    bool duplicates = true;
    bool local_slaves = true;   // false: the master's own host renders nothing
    std::string povray;
    std::string slave;
    double timeout = 120;
    int nice = 0;
    double progress = 10;
    bool quiet = false;
    std::string stats;
    std::vector<std::string> pov;   // POV-Ray options, in order
};

[[noreturn]] void usage_error(const std::string &msg)
{
    fprintf(stderr, "fc-master: %s\n%s\nTry 'fc-master --help' for more information.\n",
            msg.c_str(), kUsage);
    exit(2);
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

Options parse_options(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--help") {
            printf("%s\n\n%s", kUsage, kHelp);
            exit(0);
        }
        if (a == "-o") {
            if (i + 1 >= argc)
                usage_error("-o needs a directory");
            o.output = argv[++i];
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
                                                    "--no-local-slaves", "--quiet"};
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
            continue;
        }
        if (!valued.count(name))
            usage_error("unknown option " + name);
        if (!has_value) {
            if (i + 1 >= argc)
                usage_error("option " + name + " needs a value");
            value = argv[++i];
        }
        if (name == "--output") {
            o.output = value;
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
    return o;
}

std::string absolute(const std::string &path)
{
    char buf[PATH_MAX];
    if (realpath(path.c_str(), buf))
        return buf;
    if (!path.empty() && path[0] == '/')
        return path;
    char cwd[PATH_MAX];
    if (!getcwd(cwd, sizeof cwd))
        return path;
    return std::string(cwd) + "/" + path;
}

bool make_dirs(const std::string &dir, std::string &err)
{
    std::string acc;
    size_t pos = 0;
    while (pos <= dir.size()) {
        size_t slash = dir.find('/', pos);
        if (slash == std::string::npos)
            slash = dir.size();
        acc = dir.substr(0, slash);
        if (!acc.empty() && mkdir(acc.c_str(), 0777) != 0 && errno != EEXIST)
            return sys_fail(err, "mkdir " + acc);
        pos = slash + 1;
    }
    struct stat st;
    if (stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        err = dir + " is not a directory";
        return false;
    }
    return true;
}

// --- the master ----------------------------------------------------------------------------

enum class SlaveState { Starting, Idle, Busy, Reserved, Gone };

struct SlaveInfo {
    int tid = 0;
    int dtid = 0;               // its host's pvmd
    std::string host;
    SlaveState state = SlaveState::Starting;
    int unit = -1;
    double spawned = 0, last_msg = 0, last_ping = 0;
    double reserved_since = 0;  // Reserved: when FC_TRUNCATE went out
    bool killed = false;        // we asked PVM to kill it
    int frame = 0, px_done = 0, px_total = 0;   // from FC_PROGRESS
};

struct HostInfo {
    int dtid = 0;
    std::string name;
    int cpus = 0;               // from the first FC_HELLO; 0 = unknown
    bool alive = true;
    bool grown = false;         // extra slaves for its cores already spawned
    int respawns = 0;
};

class Master {
public:
    Master(const Options &o) : opt_(o), report_(o.progress, o.quiet) {}
    int run();

private:
    // Set-up steps, in order.
    bool resolve_programs();
    bool probe();
    bool prepare_output();
    bool start_vm();
    bool spawn_on(HostInfo &host, int count);
    void wait_for_other_hosts();
    bool spawn_all();

    // The receive loop and its handlers, one per tag.
    int loop();
    void on_hello(int src);
    void on_frame(int src);
    void on_progress(int src);
    void on_done(int src);
    void on_fail(int src);
    void on_truncated(int src);
    void on_task_exit();
    void on_host_delete();
    void on_host_add();

    // Helpers.
    void dispatch();
    void send_job(SlaveInfo &s, int unit);
    void slave_gone(SlaveInfo &s, const std::string &why, bool respawn);
    void check_timeouts();
    void progress();
    void fatal(const std::string &msg);
    void shutdown_slaves();
    void finish(bool ok);
    int index_of(int frame) const;
    int threads_for(const SlaveInfo &s) const;
    HostStat &host_stat(const std::string &name);
    SlaveInfo *slave(int tid);

    Options opt_;
    Report report_;
    std::string renderer_, slave_prog_, cwd_, outdir_, tmpdir_;
    std::vector<std::string> extra_;
    SceneInfo scene_;
    std::vector<Rect> tiles_;
    std::unique_ptr<Schedule> sched_;
    std::unique_ptr<FrameStore> store_;
    VirtualMachine vm_;
    std::map<int, SlaveInfo> slaves_;
    std::map<int, HostInfo> hosts_;         // by pvmd tid
    int my_dtid_ = 0;
    bool planned_ = false;
    double start_ = 0, spawn_time_ = 0;
    bool failed_ = false;
    std::string failure_;
    bool aa_warned_ = false;
    std::string vm_kind_ = "none";          // "private" or "running" once started
    int resumed_ = 0, rendered_ = 0;
    long cells_total_ = 0;
    std::vector<FrameStat> frame_stats_;
    std::map<int, UnitStat> unit_stats_;
    std::map<std::string, HostStat> host_stats_;
    std::map<int, int> frame_index_;
};

SlaveInfo *Master::slave(int tid)
{
    auto it = slaves_.find(tid);
    return it == slaves_.end() ? nullptr : &it->second;
}

HostStat &Master::host_stat(const std::string &name)
{
    HostStat &h = host_stats_[name];
    h.name = name;
    return h;
}

int Master::index_of(int frame) const
{
    auto it = frame_index_.find(frame);
    return it == frame_index_.end() ? -1 : it->second;
}

bool Master::resolve_programs()
{
    std::string here = self_dir();
    if (!opt_.povray.empty()) {
        renderer_ = which(opt_.povray);
        if (renderer_.empty()) {
            fprintf(stderr, "fc-master: renderer %s not found or not executable\n",
                    opt_.povray.c_str());
            return false;
        }
    } else if (const char *env = getenv("FC_POVRAY"); env && *env) {
        renderer_ = which(env);
    } else if (is_executable(here + "/povray-fc")) {
        renderer_ = here + "/povray-fc";
    } else {
        renderer_ = which("povray-fc");
        if (renderer_.empty())
            renderer_ = which("povray");
    }
    if (renderer_.empty()) {
        fprintf(stderr, "fc-master: no renderer found (povray-fc or povray); use --povray PATH\n");
        return false;
    }
    renderer_ = absolute(renderer_);

    slave_prog_ = opt_.slave.empty() ? here + "/fc-slave" : opt_.slave;
    if (slave_prog_.find('/') == std::string::npos)
        slave_prog_ = which(slave_prog_).empty() ? slave_prog_ : which(slave_prog_);
    slave_prog_ = absolute(slave_prog_);
    if (!is_executable(slave_prog_)) {
        fprintf(stderr, "fc-master: slave program %s is missing or not executable "
                        "(build it with 'make -C coordinator', or use --slave PATH)\n",
                slave_prog_.c_str());
        return false;
    }
    char buf[PATH_MAX];
    if (!getcwd(buf, sizeof buf)) {
        perror("fc-master: getcwd");
        return false;
    }
    cwd_ = buf;
    return true;
}

bool Master::probe()
{
    std::string err;
    remove_stale_dirs("/tmp", "fc-master-");
    if (!make_temp_dir("/tmp", strf("fc-master-%d-", int(getpid())), tmpdir_, err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    if (!probe_scene(renderer_, opt_.pov, cwd_, tmpdir_, std::max(30.0, opt_.timeout), scene_,
                     err)) {
        fprintf(stderr, "fc-master: %s", err.c_str());
        if (err.empty() || err.back() != '\n')
            fputc('\n', stderr);
        return false;
    }
    if (opt_.fc) {
        bool has_fc = false;
        std::string first;
        if (!renderer_version(renderer_, has_fc, first, err)) {
            fprintf(stderr, "fc-master: %s\n", err.c_str());
            return false;
        }
        if (has_fc)
            extra_.push_back(kFrameCoherenceOption);
        else
            fprintf(stderr, "fc-master: warning: %s does not support frame coherence; "
                            "rendering without it\n", renderer_.c_str());
    }
    for (size_t i = 0; i < scene_.frames.size(); i++)
        frame_index_[scene_.frames[i]] = int(i);
    if (opt_.division == Division::Sequence)
        tiles_ = {scene_.area};
    else
        tiles_ = make_tiles(scene_.area, opt_.tile);
    return true;
}

bool Master::prepare_output()
{
    outdir_ = opt_.output.empty() ? dir_name(scene_.output_name) : opt_.output;
    std::string err;
    if (!make_dirs(outdir_, err)) {
        fprintf(stderr, "fc-master: output directory: %s\n", err.c_str());
        return false;
    }
    outdir_ = absolute(outdir_);
    std::string stem = base_name(scene_.stem);
    store_.reset(new FrameStore(outdir_, stem, scene_.digits, scene_.width, scene_.height,
                                scene_.frames));
    store_->remove_stale_temps();
    sched_.reset(new Schedule(tiles_, int(scene_.frames.size())));
    cells_total_ = long(tiles_.size()) * long(scene_.frames.size());
    for (size_t i = 0; i < scene_.frames.size(); i++) {
        FrameStat fs;
        fs.frame = scene_.frames[i];
        fs.file = base_name(store_->final_path(int(i)));
        if (store_->exists_complete(int(i))) {
            fs.resumed = true;
            for (int t = 0; t < int(tiles_.size()); t++)
                sched_->mark_done(t, int(i));
            resumed_++;
        }
        frame_stats_.push_back(fs);
    }
    return true;
}

bool Master::start_vm()
{
    std::string err;
    std::string hostfile = opt_.hostfile.empty() ? "" : absolute(opt_.hostfile);
    if (!vm_.start(opt_.force_private, hostfile, opt_.pvmd_name, std::max(60.0, opt_.timeout / 2),
                   err)) {
        fprintf(stderr, "fc-master: %s\n", err.c_str());
        return false;
    }
    vm_kind_ = vm_.embedded() ? "private" : "running";
    my_dtid_ = pvm_tidtohost(vm_.mytid());
    int nhost = 0, narch = 0;
    struct pvmhostinfo *hi = nullptr;
    int r = pvm_config(&nhost, &narch, &hi);
    if (r < 0) {
        fprintf(stderr, "fc-master: pvm_config: %s\n", pvm_error(r).c_str());
        return false;
    }
    std::vector<int> dtids;
    for (int i = 0; i < nhost; i++) {
        HostInfo h;
        h.dtid = hi[i].hi_tid;
        h.name = hi[i].hi_name;
        if (h.dtid == my_dtid_)
            h.cpus = cpu_count();
        hosts_[h.dtid] = h;
        dtids.push_back(h.dtid);
    }
    r = pvm_notify(PvmHostDelete, FC_HOSTDEL, int(dtids.size()), dtids.data());
    if (r < 0)
        fprintf(stderr, "fc-master: warning: pvm_notify(PvmHostDelete): %s\n", pvm_error(r).c_str());
    r = pvm_notify(PvmHostAdd, FC_HOSTADD, -1, nullptr);
    if (r < 0)
        fprintf(stderr, "fc-master: warning: pvm_notify(PvmHostAdd): %s\n", pvm_error(r).c_str());
    return true;
}

// With --no-local-slaves only other hosts render, and a private pvmd adds the hosts of its
// hostfile in the background: wait (bounded) until one has joined.
void Master::wait_for_other_hosts()
{
    double deadline = now() + std::max(30.0, opt_.timeout / 2);
    while (now() < deadline) {
        int nhost = 0, narch = 0;
        struct pvmhostinfo *hi = nullptr;
        if (pvm_config(&nhost, &narch, &hi) < 0)
            return;
        bool other = false;
        for (int i = 0; i < nhost; i++) {
            if (hi[i].hi_tid == my_dtid_ || hosts_.count(hi[i].hi_tid))
                continue;
            HostInfo h;
            h.dtid = hi[i].hi_tid;
            h.name = hi[i].hi_name;
            hosts_[h.dtid] = h;
            pvm_notify(PvmHostDelete, FC_HOSTDEL, 1, &h.dtid);
        }
        for (auto &kv : hosts_)
            other = other || kv.first != my_dtid_;
        if (other)
            return;
        usleep(200000);
    }
}

bool Master::spawn_on(HostInfo &host, int count)
{
    std::vector<int> tids(size_t(count), 0);
    char *args[] = {nullptr};
    int n = pvm_spawn(const_cast<char *>(slave_prog_.c_str()), args, PvmTaskHost,
                      const_cast<char *>(host.name.c_str()), count, tids.data());
    std::vector<int> ok;
    for (int i = 0; i < count; i++) {
        if (i < std::max(n, 0) && tids[size_t(i)] > 0) {
            ok.push_back(tids[size_t(i)]);
        } else {
            int code = n < 0 ? n : tids[size_t(i)];
            fprintf(stderr, "fc-master: cannot start %s on host %s: %s\n", slave_prog_.c_str(),
                    host.name.c_str(), pvm_error(code).c_str());
            if (code == PvmNoFile)
                fprintf(stderr, "fc-master: the slave program must exist at the same absolute "
                                "path on every host\n");
            break;
        }
    }
    if (ok.empty())
        return false;
    int r = pvm_notify(PvmTaskExit, FC_TASKEXIT, int(ok.size()), ok.data());
    if (r < 0)
        fprintf(stderr, "fc-master: warning: pvm_notify(PvmTaskExit): %s\n", pvm_error(r).c_str());
    double t = now();
    for (int tid : ok) {
        SlaveInfo s;
        s.tid = tid;
        s.dtid = host.dtid;
        s.host = host.name;
        s.spawned = s.last_msg = t;
        slaves_[tid] = s;
        host_stat(host.name).slaves++;
    }
    return int(ok.size()) == count;
}

bool Master::spawn_all()
{
    if (!opt_.local_slaves)
        wait_for_other_hosts();
    spawn_time_ = now();
    bool any = false;
    for (auto &kv : hosts_) {
        HostInfo &h = kv.second;
        if (!opt_.local_slaves && h.dtid == my_dtid_)
            continue;
        int n = opt_.slaves > 0 ? opt_.slaves : (h.cpus > 0 ? h.cpus : 1);
        if (opt_.slaves > 0 || h.cpus > 0)
            h.grown = true;
        spawn_on(h, n);
        any = any || std::any_of(slaves_.begin(), slaves_.end(),
                                 [&](auto &s) { return s.second.dtid == h.dtid; });
    }
    if (!any) {
        fprintf(stderr, "fc-master: no slave could be started\n");
        return false;
    }
    return true;
}

int Master::threads_for(const SlaveInfo &s) const
{
    auto h = hosts_.find(s.dtid);
    int cpus = h == hosts_.end() ? 1 : std::max(1, h->second.cpus);
    int n = 0;
    for (auto &kv : slaves_)
        if (kv.second.dtid == s.dtid && kv.second.state != SlaveState::Gone)
            n++;
    return std::max(1, cpus / std::max(1, n));
}

void Master::send_job(SlaveInfo &s, int id)
{
    const Unit &u = sched_->unit(id);
    Job j;
    j.unit = id;
    j.rect = sched_->tile(u.tile);
    j.first = scene_.frames[size_t(u.lo)];
    j.last = scene_.frames[size_t(u.hi)];
    j.step = scene_.digits > 0 ? scene_.frame_step : 1;
    j.threads = threads_for(s);
    int r = send_msg(s.tid, FC_JOB, j);
    debug_log("FC_JOB unit %d tile %d frames %d..%d to t%x", id, u.tile, j.first, j.last,
              unsigned(s.tid));
    s.state = SlaveState::Busy;
    s.unit = id;
    s.last_msg = now();
    s.px_done = s.px_total = 0;
    UnitStat &us = unit_stats_[id];
    us.id = id;
    us.tile = u.tile;
    us.rect = j.rect;
    us.first = j.first;
    us.last = j.last;
    us.host = s.host;
    us.tid = s.tid;
    us.dup_of = u.dup_of;
    us.started = now();
    host_stat(s.host).units++;
    if (r < 0)
        slave_gone(s, "cannot send it work: " + pvm_error(r), false);
}

// Hand work to every idle slave: queued units first, then splits, then duplicates.
void Master::dispatch()
{
    if (failed_ || g_signal)
        return;
    if (!planned_) {
        int ready = 0, starting = 0;
        for (auto &kv : slaves_) {
            if (kv.second.state == SlaveState::Starting) starting++;
            else if (kv.second.state != SlaveState::Gone) ready++;
        }
        // Cut the initial ranges for the slaves we have, once all said hello (or 5 s passed).
        if (ready == 0 || (starting > 0 && now() - spawn_time_ < 5))
            return;
        int parts = opt_.ranges > 0 ? opt_.ranges : ready;
        sched_->plan(opt_.division, parts);
        planned_ = true;
    }
    if (sched_->queued() == 0 && sched_->running() == 0 && !sched_->finished()) {
        // Nothing queued or running, yet frames are missing: a bug; do not hang on it.
        int n = sched_->repair();
        if (n > 0) {
            report_.clear_line();
            fprintf(stderr, "fc-master: warning: %d piece(s) of work were lost track of and "
                            "are queued again\n", n);
        }
    }
    for (auto &kv : slaves_) {
        SlaveInfo &s = kv.second;
        if (s.state != SlaveState::Idle)
            continue;
        Action a = sched_->next_for(s.tid, now(), opt_.duplicates);
        if (a.kind == Action::Run) {
            send_job(s, a.unit);
        } else if (a.kind == Action::Split) {
            Unit &u = sched_->unit(a.unit);
            Truncate t;
            t.unit = a.unit;
            t.last = scene_.frames[size_t(a.new_hi)];
            int r = send_msg(u.slave, FC_TRUNCATE, t);
            s.reserved_since = now();
            debug_log("FC_TRUNCATE unit %d to frame %d (t%x), t%x waits", a.unit, t.last,
                      unsigned(u.slave), unsigned(s.tid));
            s.state = SlaveState::Reserved;
            s.unit = a.unit;
            if (r < 0) {
                int reserved = 0;
                sched_->truncated(a.unit, -1, reserved);
                s.state = SlaveState::Idle;
            }
        }
    }
}

void Master::on_hello(int src)
{
    Hello h;
    SlaveInfo *s = slave(src);
    if (!unpack(h) || !s || s->state != SlaveState::Starting)
        return;
    s->state = SlaveState::Idle;
    HostInfo &host = hosts_[s->dtid];
    if (host.cpus == 0)
        host.cpus = std::max(1, h.cpus);
    Setup setup;
    setup.renderer = renderer_;
    setup.cwd = cwd_;
    setup.options = opt_.pov;
    setup.extra = extra_;
    setup.width = scene_.width;
    setup.height = scene_.height;
    setup.digits = scene_.digits;
    setup.timeout = int(std::ceil(opt_.timeout));
    setup.nice = opt_.nice;
    int r = send_msg(src, FC_SETUP, setup);
    if (r < 0) {
        slave_gone(*s, "cannot send it the setup: " + pvm_error(r), false);
        return;
    }
    // A host whose core count we just learned gets one slave per core.
    if (!host.grown && host.alive) {
        host.grown = true;
        if (host.cpus > 1)
            spawn_on(host, host.cpus - 1);
    }
    dispatch();
}

void Master::on_frame(int src)
{
    FrameResult fr;
    SlaveInfo *s = slave(src);
    if (!unpack(fr)) {
        fprintf(stderr, "fc-master: warning: malformed FC_FRAME from t%x\n", unsigned(src));
        return;
    }
    if (s)
        s->last_msg = now();
    int idx = index_of(fr.frame);
    const Unit *u = sched_->find(fr.unit);
    if (idx < 0 || !u || !(sched_->tile(u->tile) == fr.rect)) {
        fprintf(stderr, "fc-master: warning: unexpected frame %d for unit %d from t%x\n",
                fr.frame, fr.unit, unsigned(src));
        return;
    }
    int tile = u->tile;
    std::vector<int> cancel;
    bool fresh = sched_->frame_arrived(fr.unit, idx, cancel);
    UnitStat &us = unit_stats_[fr.unit];
    us.frames++;
    us.rays += fr.rays;
    std::string host = s ? s->host : "?";
    HostStat &hs = host_stat(host);
    hs.frames++;
    hs.rays += fr.rays;
    if (fresh) {
        CellStat c;
        c.tile = tile;
        c.unit = fr.unit;
        c.host = host;
        c.rays = fr.rays;
        c.seconds = fr.seconds;
        frame_stats_[size_t(idx)].cells.push_back(c);
        store_->put(idx, fr.rect, fr.pixels);
        if (sched_->frame_done(idx)) {
            std::string err;
            if (!store_->write(idx, err)) {
                fatal(err);
                return;
            }
            frame_stats_[size_t(idx)].finished_at = now() - start_;
            rendered_++;
        }
    }
    if (fr.aa_method == 1 && tiles_.size() > 1 && opt_.tile % 32 != 0 && !aa_warned_) {
        aa_warned_ = true;
        report_.clear_line();
        fprintf(stderr, "fc-master: warning: antialiasing method 1 works on 32-pixel blocks; "
                        "tiles of %d pixels can change a few pixels compared with a "
                        "single-process render (use --tile 64 or 96, +AM2, or --division "
                        "sequence for identical pixels)\n", opt_.tile);
    }
    for (int id : cancel) {
        const Unit &v = sched_->unit(id);
        debug_log("FC_CANCEL unit %d to t%x", id, unsigned(v.slave));
        if (pack_int(id) >= 0)
            send_packed(v.slave, FC_CANCEL);
    }
}

void Master::on_progress(int src)
{
    Progress p;
    SlaveInfo *s = slave(src);
    if (!unpack(p) || !s)
        return;
    s->last_msg = now();
    s->frame = p.frame;
    s->px_done = p.done;
    s->px_total = p.total;
}

void Master::on_done(int src)
{
    UnitDone d;
    SlaveInfo *s = slave(src);
    if (!unpack(d) || !s)
        return;
    debug_log("FC_DONE unit %d status %d frames %d from t%x", d.unit, d.status, d.frames,
              unsigned(src));
    s->last_msg = now();
    const Unit *u = sched_->find(d.unit);
    if (u && u->live && u->slave == src) {
        UnitStat &us = unit_stats_[d.unit];
        us.status = d.status == UNIT_CANCELLED ? "cancelled"
                  : d.status == UNIT_TRUNCATED ? "truncated" : "finished";
        us.last = scene_.frames[size_t(u->hi)];
        us.seconds = d.seconds;
        host_stat(s->host).busy += d.seconds;
        // A finished unit should have delivered every cell of its range; anything missing
        // (renderer output lost) is re-queued by unit_ended.
        for (int i = u->lo; i <= u->hi; i++)
            if (!sched_->done(u->tile, i))
                debug_log("unit %d finished without frame %d", d.unit, scene_.frames[size_t(i)]);
        int reserved = sched_->unit_ended(d.unit);
        if (SlaveInfo *r = slave(reserved); r && r->state == SlaveState::Reserved)
            r->state = SlaveState::Idle;
    }
    if (s->state == SlaveState::Busy && s->unit == d.unit) {
        s->state = SlaveState::Idle;
        s->unit = -1;
    }
    dispatch();
}

void Master::on_fail(int src)
{
    Failure f;
    SlaveInfo *s = slave(src);
    if (!unpack(f))
        return;
    std::string host = s ? s->host : "?";
    if (f.unit >= 0 && unit_stats_.count(f.unit))
        unit_stats_[f.unit].status = "failed";
    std::string what = f.status == -1 ? "slave error" : describe_status(f.status);
    std::string msg = strf("rendering failed on host %s (frame %d, %s):\n%s", host.c_str(),
                          f.frame, what.c_str(), f.message.c_str());
    fatal(msg);
}

void Master::on_truncated(int src)
{
    Truncate t;
    SlaveInfo *s = slave(src);
    if (!unpack(t))
        return;
    if (s)
        s->last_msg = now();
    int accepted = t.last < 0 ? -1 : index_of(t.last);
    int reserved = 0;
    int tail = sched_->truncated(t.unit, accepted, reserved);
    debug_log("FC_TRUNCATED unit %d at frame %d: tail unit %d for t%x", t.unit, t.last, tail,
              unsigned(reserved));
    if (tail >= 0 && unit_stats_.count(t.unit))
        unit_stats_[t.unit].last = t.last;
    SlaveInfo *r = slave(reserved);
    if (r && r->state == SlaveState::Reserved) {
        r->state = SlaveState::Idle;
        r->unit = -1;
        if (tail >= 0) {
            sched_->assign(tail, r->tid, now());
            send_job(*r, tail);
        }
    }
    dispatch();
}

// A slave is gone (exited, killed, its host died): put its work back.
void Master::slave_gone(SlaveInfo &s, const std::string &why, bool respawn)
{
    if (s.state == SlaveState::Gone)
        return;
    SlaveState was = s.state;
    s.state = SlaveState::Gone;
    if (failed_ || g_signal || (sched_ && sched_->finished()))
        return;
    report_.clear_line();
    fprintf(stderr, "fc-master: slave t%x on %s %s", unsigned(s.tid), s.host.c_str(), why.c_str());
    if (was == SlaveState::Busy && s.unit >= 0) {
        if (unit_stats_.count(s.unit))
            unit_stats_[s.unit].status = "lost";
        int reserved = sched_->unit_ended(s.unit);
        if (SlaveInfo *r = slave(reserved); r && r->state == SlaveState::Reserved)
            r->state = SlaveState::Idle;
        fprintf(stderr, "; its unfinished frames are queued again");
    }
    fprintf(stderr, "\n");
    s.unit = -1;
    // Replace a slave that exited while its host lives (a few times per host). Not one that
    // fell silent: its host may be unreachable, and pvm_spawn there blocks until PVM gives
    // up on the host (minutes).
    auto h = hosts_.find(s.dtid);
    if (respawn && h != hosts_.end() && h->second.alive && h->second.respawns < 3) {
        h->second.respawns++;
        spawn_on(h->second, 1);
    }
    dispatch();
}

void Master::on_task_exit()
{
    int tid = 0;
    if (!unpack_int(tid))
        return;
    if (SlaveInfo *s = slave(tid))
        slave_gone(*s, "exited", true);
}

void Master::on_host_delete()
{
    int dtid = 0;
    if (!unpack_int(dtid))
        return;
    auto h = hosts_.find(dtid);
    if (h == hosts_.end())
        return;
    h->second.alive = false;
    for (auto &kv : slaves_)
        if (kv.second.dtid == dtid)
            slave_gone(kv.second, "was lost with its host", false);
}

void Master::on_host_add()
{
    int n = 0;
    if (!unpack_int(n) || n <= 0)
        return;
    std::vector<int> added(size_t(n), 0);
    if (pvm_upkint(added.data(), n, 1) < 0)
        return;
    int nhost = 0, narch = 0;
    struct pvmhostinfo *hi = nullptr;
    if (pvm_config(&nhost, &narch, &hi) < 0)
        return;
    for (int dtid : added) {
        for (int i = 0; i < nhost; i++) {
            if (hi[i].hi_tid != dtid || hosts_.count(dtid))
                continue;
            HostInfo h;
            h.dtid = dtid;
            h.name = hi[i].hi_name;
            hosts_[dtid] = h;
            pvm_notify(PvmHostDelete, FC_HOSTDEL, 1, &dtid);
            report_.clear_line();
            fprintf(stderr, "fc-master: host %s joined\n", h.name.c_str());
            if (!sched_->finished() && !failed_) {
                HostInfo &hr = hosts_[dtid];
                if (opt_.slaves > 0)
                    hr.grown = true;
                spawn_on(hr, opt_.slaves > 0 ? opt_.slaves : 1);
            }
        }
    }
}

void Master::check_timeouts()
{
    // Messages still waiting mean the master itself was slow (a blocking PVM call): read
    // them before judging anybody silent.
    if (pvm_probe(-1, -1) > 0)
        return;
    double t = now();
    double split_wait = std::min(10.0, opt_.timeout / 2);
    bool redispatch = false;
    for (auto &kv : slaves_) {
        SlaveInfo &s = kv.second;
        if (s.state == SlaveState::Gone || s.killed)
            continue;
        bool silent = (s.state == SlaveState::Starting || s.state == SlaveState::Busy) &&
                      t - s.last_msg > opt_.timeout;
        if (silent) {
            // Its work is re-queued right away. On this host SIGKILL also ends a stopped
            // process. A remote one is only abandoned: pvm_sendsig waits for the remote pvmd,
            // which blocks until PVM declares a crashed host dead (minutes); if it lives, it
            // exits when the master does (FC_MASTEREXIT).
            s.killed = true;
            if (s.dtid == my_dtid_)
                pvm_sendsig(s.tid, SIGKILL);
            slave_gone(s, strf("was silent for %.0f s and is %s", t - s.last_msg,
                               s.dtid == my_dtid_ ? "stopped" : "abandoned"), false);
        } else if (s.state == SlaveState::Reserved && t - s.reserved_since > split_wait) {
            // The busy slave did not answer FC_TRUNCATE: do not wait for it any longer.
            debug_log("FC_TRUNCATE of unit %d unanswered; t%x is idle again", s.unit,
                      unsigned(s.tid));
            sched_->truncate_timed_out(s.unit);
            s.state = SlaveState::Idle;
            s.unit = -1;
            redispatch = true;
        }
        if ((s.state == SlaveState::Idle || s.state == SlaveState::Reserved) &&
            t - std::max(s.last_ping, s.last_msg) > std::max(1.0, opt_.timeout / 3)) {
            s.last_ping = t;
            if (pack_empty() >= 0)
                send_packed(s.tid, FC_PING);
        }
    }
    if (redispatch)
        dispatch();
}

void Master::progress()
{
    int busy = 0, alive = 0;
    double partial = 0;
    for (auto &kv : slaves_) {
        const SlaveInfo &s = kv.second;
        if (s.state == SlaveState::Gone)
            continue;
        alive++;
        if (s.state == SlaveState::Busy) {
            busy++;
            if (s.px_total > 0)
                partial += double(s.px_done) / s.px_total;
        }
    }
    long cells_done = 0;
    for (int i = 0; i < sched_->frames(); i++)
        for (int tl = 0; tl < sched_->tiles(); tl++)
            cells_done += sched_->done(tl, i) ? 1 : 0;
    double frac = cells_total_ > 0 ? std::min(1.0, (cells_done + partial) / cells_total_) : 1;
    report_.progress(now() - start_, sched_->frames_done(), sched_->frames(), frac, busy, alive);
}

void Master::fatal(const std::string &msg)
{
    if (failed_)
        return;     // report the first error only
    failed_ = true;
    failure_ = msg;
    report_.clear_line();
    fprintf(stderr, "fc-master: %s", msg.c_str());
    if (msg.empty() || msg.back() != '\n')
        fputc('\n', stderr);
    shutdown_slaves();
}

// Tell every slave to quit, wait (bounded) for them to go, kill stragglers.
void Master::shutdown_slaves()
{
    std::vector<int> live;
    for (auto &kv : slaves_)
        if (kv.second.state != SlaveState::Gone)
            live.push_back(kv.first);
    for (int tid : live)
        if (pack_empty() >= 0)
            send_packed(tid, FC_QUIT);
    double deadline = now() + 5;
    std::set<int> waiting(live.begin(), live.end());
    while (!waiting.empty() && now() < deadline) {
        struct timeval tv = {0, 200000};
        int buf = pvm_trecv(-1, FC_TASKEXIT, &tv);
        if (buf < 0)
            break;
        if (buf == 0)
            continue;
        int tid = 0;
        if (unpack_int(tid)) {
            waiting.erase(tid);
            if (SlaveInfo *s = slave(tid))
                s->state = SlaveState::Gone;
        }
    }
    for (int tid : waiting) {
        SlaveInfo *s = slave(tid);
        if (s && s->dtid == my_dtid_)   // remote ones exit on FC_MASTEREXIT (see check_timeouts)
            pvm_sendsig(tid, SIGKILL);
        if (s)
            s->state = SlaveState::Gone;
    }
}

int Master::loop()
{
    start_ = now();
    while (!sched_->finished() && !failed_) {
        if (g_signal) {
            report_.clear_line();
            fprintf(stderr, "fc-master: interrupted (%s): stopping the slaves\n",
                    strsignal(g_signal));
            shutdown_slaves();
            return 128 + g_signal;
        }
        struct timeval tv = {0, 250000};
        int buf = pvm_trecv(-1, -1, &tv);
        if (buf < 0) {
            fatal("lost contact with the PVM daemon: " + pvm_error(buf));
            break;
        }
        if (buf > 0) {
            int len = 0, tag = 0, src = 0;
            pvm_bufinfo(buf, &len, &tag, &src);
            debug_log("recv %s from t%x (%d bytes)", tag_name(tag), unsigned(src), len);
            switch (tag) {
            case FC_HELLO: on_hello(src); break;
            case FC_FRAME: on_frame(src); break;
            case FC_PROGRESS: on_progress(src); break;
            case FC_DONE: on_done(src); break;
            case FC_FAIL: on_fail(src); break;
            case FC_TRUNCATED: on_truncated(src); break;
            case FC_TASKEXIT: on_task_exit(); break;
            case FC_HOSTDEL: on_host_delete(); break;
            case FC_HOSTADD: on_host_add(); break;
            default:
                fprintf(stderr, "fc-master: warning: unexpected message %s (%d) from t%x\n",
                        tag_name(tag), tag, unsigned(src));
            }
        }
        if (failed_)
            break;
        if (!planned_)
            dispatch();
        check_timeouts();
        bool anyone = std::any_of(slaves_.begin(), slaves_.end(),
                                  [](auto &kv) { return kv.second.state != SlaveState::Gone; });
        if (!anyone && !sched_->finished()) {
            fatal("no slave is left to render the remaining frames");
            break;
        }
        progress();
    }
    if (failed_)
        return 1;
    report_.clear_line();
    shutdown_slaves();
    return 0;
}

void Master::finish(bool ok)
{
    // Units still running at the end (straggler copies, or an abort) count until now.
    for (auto &kv : unit_stats_) {
        UnitStat &u = kv.second;
        if (u.status != "running")
            continue;
        u.status = "stopped";
        u.seconds = now() - u.started;
        host_stat(u.host).busy += u.seconds;
    }
    // Distinct frames each host contributed pixels to.
    std::map<std::string, std::set<int>> touched;
    for (const FrameStat &f : frame_stats_)
        for (const CellStat &c : f.cells)
            touched[c.host].insert(f.frame);
    for (auto &kv : host_stats_) {
        kv.second.tiles = kv.second.frames;
        kv.second.frames = int(touched[kv.first].size());
    }
    if (!opt_.stats.empty() && sched_) {
        std::string head;
        head += "  \"scene\": " + Report::json_string(opt_.pov.empty() ? "" : opt_.pov[0]) + ",\n";
        head += "  \"renderer\": " + Report::json_string(renderer_) + ",\n";
        head += "  \"output\": " + Report::json_string(outdir_) + ",\n";
        head += strf("  \"division\": \"%s\",\n", division_name(opt_.division));
        head += strf("  \"tile\": %d,\n  \"width\": %d,\n  \"height\": %d,\n", opt_.tile,
                    scene_.width, scene_.height);
        head += strf("  \"frame_coherence\": %s,\n", extra_.empty() ? "false" : "true");
        head += strf("  \"virtual_machine\": \"%s\",\n  \"hosts_used\": %d,\n",
                     vm_kind_.c_str(), int(hosts_.size()));
        head += strf("  \"success\": %s,\n", ok ? "true" : "false");
        head += strf("  \"elapsed\": %.3f,\n", start_ > 0 ? now() - start_ : 0.0);
        head += strf("  \"frames_total\": %d,\n  \"frames_rendered\": %d,\n  \"frames_resumed\": %d,\n",
                    int(scene_.frames.size()), rendered_, resumed_);
        std::string err;
        if (!report_.write_json(opt_.stats, head, frame_stats_, unit_stats_, host_stats_, err))
            fprintf(stderr, "fc-master: cannot write statistics: %s\n", err.c_str());
    }
}

int Master::run()
{
    if (!resolve_programs() || !probe() || !prepare_output()) {
        if (!tmpdir_.empty())
            remove_tree(tmpdir_);
        return 1;
    }
    remove_tree(tmpdir_);
    tmpdir_.clear();
    if (sched_->finished()) {
        fprintf(stderr, "fc-master: all %zu frame(s) already exist in %s: nothing to render\n",
                scene_.frames.size(), outdir_.c_str());
        finish(true);
        return 0;
    }
    if (!start_vm()) {
        vm_.stop();
        return 1;
    }
    int rc = spawn_all() ? loop() : 1;
    double elapsed = start_ > 0 ? now() - start_ : 0;
    if (rc != 0)
        shutdown_slaves();
    vm_.stop();
    finish(rc == 0);
    if (rc == 0 && !opt_.quiet) {
        fputs(report_.summary(elapsed, rendered_, resumed_, division_name(opt_.division),
                              host_stats_).c_str(), stderr);
        fprintf(stderr, "  (%zu host(s) of a %s virtual machine)\n", hosts_.size(),
                vm_kind_ == "private" ? "private" : "running");
    }
    return rc;
}

} // namespace

int main(int argc, char **argv)
{
    Options opt = parse_options(argc, argv);
    install_signal_handlers(on_signal);
    Master master(opt);
    return master.run();
}
