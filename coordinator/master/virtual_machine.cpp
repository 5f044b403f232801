// virtual_machine.cpp - join or start a PVM virtual machine (see virtual_machine.h).
#include "virtual_machine.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <netdb.h>
#include <netinet/in.h>
#include <arpa/inet.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <pvm3.h>

#include "clock.h"
#include "files.h"
#include "host_info.h"
#include "pvm_error.h"
#include "temp_dirs.h"
#include "text.h"
#include "watchdog.h"

namespace fc {

namespace {

// Can we connect to addr within a second? addr is what a pvmd writes into pvmd.<uid>: the path
// of its Unix socket, or its TCP address as hex "address:port".
bool pvmd_answers(const std::string &addr, bool &understood)
{
    understood = true;
    if (!addr.empty() && addr[0] == '/') {
        int s = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (s < 0)
            return false;
        struct sockaddr_un sa;
        memset(&sa, 0, sizeof sa);
        sa.sun_family = AF_UNIX;
        strncpy(sa.sun_path, addr.c_str(), sizeof sa.sun_path - 1);
        bool ok = connect(s, reinterpret_cast<struct sockaddr *>(&sa), sizeof sa) == 0;
        close(s);
        return ok;
    }
    unsigned ip = 0, port = 0;
    char tail;
    if (sscanf(addr.c_str(), "%x:%x%c", &ip, &port, &tail) != 2 || port == 0 || port > 65535) {
        understood = false;
        return true;
    }
    int s = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (s < 0)
        return false;
    struct sockaddr_in sa;
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_addr.s_addr = htonl(ip);
    sa.sin_port = htons(uint16_t(port));
    bool ok = connect(s, reinterpret_cast<struct sockaddr *>(&sa), sizeof sa) == 0;
    if (!ok && errno == EINPROGRESS) {
        struct pollfd p = {s, POLLOUT, 0};
        int soerr = 0;
        socklen_t len = sizeof soerr;
        ok = poll(&p, 1, 1000) == 1 && getsockopt(s, SOL_SOCKET, SO_ERROR, &soerr, &len) == 0 &&
             soerr == 0;
    }
    close(s);
    return ok;
}

// A pvmd process of ours that uses pvm_tmp (PVM_TMP in its environment, /tmp when unset).
int pvmd_process(const std::string &pvm_tmp)
{
    DIR *d = opendir("/proc");
    if (!d)
        return 0;
    int found = 0;
    while (struct dirent *e = readdir(d)) {
        int pid = atoi(e->d_name);
        if (pid <= 0)
            continue;
        std::string base = strf("/proc/%d", pid), comm, env, err;
        struct stat st;
        if (stat(base.c_str(), &st) != 0 || st.st_uid != getuid() ||
            !read_text(base + "/comm", comm, err) || trim(comm).compare(0, 4, "pvmd") != 0)
            continue;
        std::string tmp = "/tmp";
        if (read_text(base + "/environ", env, err)) {
            size_t pos = 0;
            while (pos < env.size()) {
                size_t end = env.find('\0', pos);
                std::string var = env.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
                if (starts_with(var, "PVM_TMP=") && var.size() > 8)
                    tmp = var.substr(8);
                pos = end == std::string::npos ? env.size() : end + 1;
            }
        }
        if (tmp == pvm_tmp) {
            found = pid;
            break;
        }
    }
    closedir(d);
    return found;
}

// Is a pvmd listening behind this PVM_TMP? Its pvmd.<uid> file names its socket. A file left
// behind by a killed pvmd makes libpvm retry for some 13 s and fail, and the next pvmd started
// there hang: when no pvmd of ours owns the file, remove it (saying so); when one does but
// does not answer, say what to do.
bool pvmd_alive(const std::string &pvm_tmp)
{
    std::string file = pvm_tmp + strf("/pvmd.%d", int(getuid()));
    std::string text, err;
    if (!read_text(file, text, err))
        return false;
    std::string addr = trim(text.substr(0, text.find_first_of("\r\n")));
    bool understood = true;
    if (pvmd_answers(addr, understood))
        return true;
    int pid = pvmd_process(pvm_tmp);
    if (pid > 0) {
        fprintf(stderr, "fc-master: warning: pvmd (pid %d) owns %s but does not answer; starting a "
                        "private virtual machine (stop that pvmd with 'kill %d' and remove %s to "
                        "use the shared one)\n", pid, file.c_str(), pid, file.c_str());
        return false;
    }
    if (unlink(file.c_str()) == 0)
        fprintf(stderr, "fc-master: removed %s, left behind by a pvmd that is gone\n",
                file.c_str());
    else
        fprintf(stderr, "fc-master: warning: %s is left behind by a pvmd that is gone; remove it "
                        "(%s)\n", file.c_str(), strerror(errno));
    return false;
}

// Whether process pid is stopped (SIGSTOP, or traced): its state in /proc/PID/stat.
bool process_stopped(int pid)
{
    std::string stat, err;
    if (!read_text(strf("/proc/%d/stat", pid), stat, err))
        return false;
    size_t paren = stat.rfind(')');
    if (paren == std::string::npos || paren + 2 >= stat.size())
        return false;
    char state = stat[paren + 2];
    return state == 'T' || state == 't';
}

// What to do about a pvmd that does not answer.
std::string pvmd_hint(const std::string &pvm_tmp, int pid)
{
    std::string file = pvm_tmp + strf("/pvmd.%d", int(getuid()));
    if (pid <= 0)
        return "the PVM daemon behind " + file + " does not answer: stop it and remove " + file +
               ", or use --private";
    return strf("the PVM daemon (pid %d, PVM_TMP=%s) does not answer: if it is stopped, "
                "'kill -CONT %d'; else stop it ('kill %d') and remove %s; or use --private",
                pid, pvm_tmp.c_str(), pid, pid, file.c_str());
}

std::string pvmd_program()
{
    const char *root = getenv("PVM_ROOT");
    if (root && *root) {
        std::string p = std::string(root) + "/lib/pvmd";
        if (is_executable(p))
            return p;
    }
    std::string p = which("pvmd");
    if (!p.empty())
        return p;
    return "/usr/lib/pvm3/lib/pvmd";
}

const char *const kPrivatePrefix = "fc-pvm-";

} // namespace

void remove_stale_private_vms()
{
    remove_stale_dirs(temp_root(), kPrivatePrefix);
}

bool VirtualMachine::start(bool force_private, const std::string &hostfile,
                           const std::string &name, double timeout, std::string &err)
{
    pvm_setopt(PvmAutoErr, 0);
    add_timeout_ = timeout;
    if (!force_private) {
        const char *t = getenv("PVM_TMP");
        std::string pvm_tmp = (t && *t) ? t : "/tmp";
        if (pvmd_alive(pvm_tmp)) {
            if (geteuid() == 0 && !getenv("PVM_ALLOW_ROOT"))
                setenv("PVM_ALLOW_ROOT", "1", 1);
            // A stopped pvmd still accepts connections (the kernel does), and libpvm then
            // waits for its answer forever.
            int pid = pvmd_process(pvm_tmp);
            std::string hint = pvmd_hint(pvm_tmp, pid);
            if (pid > 0 && process_stopped(pid)) {
                err = strf("the PVM daemon (pid %d, PVM_TMP=%s) is stopped: resume it ('kill "
                           "-CONT %d'), or stop it ('kill %d') and remove %s/pvmd.%d; or use "
                           "--private", pid, pvm_tmp.c_str(), pid, pid, pvm_tmp.c_str(),
                           int(getuid()));
                return false;
            }
            watchdog::set_pvm_hint(hint);
            {
                watchdog::Guard guard("pvm_mytid", watchdog::kLocalPvmBound);
                mytid_ = pvm_mytid();
            }
            if (mytid_ < 0) {
                err = "cannot join the running virtual machine (PVM_TMP=" + pvm_tmp +
                      "): pvm_mytid: " + pvm_error(mytid_);
                return false;
            }
            embedded_ = false;
            return hostfile.empty() || add_hosts(hostfile, err);
        }
    }
    return start_private(hostfile, name, timeout, err) && (hostfile.empty() || add_hosts(hostfile, err));
}

std::vector<std::string> hostfile_hosts(const std::string &hostfile)
{
    std::vector<std::string> names;
    FILE *f = fopen(hostfile.c_str(), "r");
    if (!f)
        return names;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        char name[512];
        if (sscanf(line, " %511s", name) == 1 && name[0] != '#' && name[0] != '*' &&
            name[0] != '&')
            names.push_back(name);
    }
    fclose(f);
    return names;
}

namespace {

// What to do about a host pvm_addhosts could not add.
const char *add_host_hint(int code)
{
    switch (code) {
    case PvmNoHost:
    case PvmBadParam:
        return "the name does not resolve on this machine (check /etc/hosts)";
    case PvmCantStart:
        return "no pvmd could be started there: check ssh access (PVM_RSH=/usr/bin/ssh), that "
               "PVM is installed there, and that no stale pvmd.<uid> file is left in its PVM_TMP";
    case PvmIPLoopback:
        return "this machine's name resolves to a loopback address: give the master pvmd a "
               "name with a real address (--pvmd-name NAME)";
    case PvmDSysErr:
    case PvmHostFail:
        return "the remote pvmd failed to start or answer";
    default:
        return "";
    }
}

} // namespace

bool VirtualMachine::add_hosts(const std::string &hostfile, std::string &err)
{
    std::vector<std::string> names = hostfile_hosts(hostfile);
    if (names.empty())
        return true;
    // Names are resolved here first: a pvmd whose own name is a loopback address reports
    // every host as PvmIPLoopback, hiding the more basic mistake of a name that does not
    // resolve at all.
    std::string unknown;
    for (const std::string &n : names) {
        struct addrinfo hints, *res = nullptr;
        memset(&hints, 0, sizeof hints);
        hints.ai_family = AF_INET;      // PVM 3 speaks IPv4 only
        int e = getaddrinfo(n.c_str(), nullptr, &hints, &res);
        if (res)
            freeaddrinfo(res);
        if (e != 0)
            unknown += strf("\n  %s: the name does not resolve on this machine (%s; check "
                            "/etc/hosts)", n.c_str(), gai_strerror(e));
    }
    if (!unknown.empty()) {
        err = "cannot add the host(s) of " + hostfile + " to the virtual machine:" + unknown;
        stop();
        return false;
    }
    std::vector<char *> argv;
    for (std::string &n : names)
        argv.push_back(&n[0]);
    std::vector<int> info(names.size(), 0);
    int r = 0;
    {
        // pvm_addhosts starts each host's pvmd over PVM_RSH and waits for all of them.
        watchdog::Guard guard("pvm_addhosts", std::max(60.0, add_timeout_),
                              "adding the hosts of " + hostfile + " goes through PVM_RSH (" +
                                  std::string(getenv("PVM_RSH") ? getenv("PVM_RSH") : "rsh") +
                                  "): check that each host answers it, or leave it out");
        r = pvm_addhosts(argv.data(), int(argv.size()), info.data());
    }
    std::string failed;
    for (size_t i = 0; i < names.size(); i++) {
        int code = r < 0 ? r : info[i];
        // A host already in the machine (the master's own, or one added before) is fine.
        if (code >= 0 || code == PvmDupHost || code == PvmAlready)
            continue;
        std::string hint = add_host_hint(code);
        failed += strf("\n  %s: %s%s%s", names[i].c_str(), pvm_error(code).c_str(),
                       hint.empty() ? "" : ": ", hint.c_str());
    }
    if (failed.empty())
        return true;
    err = "cannot add the host(s) of " + hostfile + " to the virtual machine:" + failed;
    stop();
    return false;
}

bool VirtualMachine::start_private(const std::string &hostfile, const std::string &name,
                                   double timeout, std::string &err)
{
    remove_stale_private_vms();
    if (!make_temp_dir(temp_root(), strf("%s%d-", kPrivatePrefix, int(getpid())), tmpdir_, err))
        return false;
    // Every program of this virtual machine (pvmd, master, slaves) must see the same PVM_TMP;
    // slaves inherit the pvmd's environment.
    setenv("PVM_TMP", tmpdir_.c_str(), 1);
    if (geteuid() == 0)
        setenv("PVM_ALLOW_ROOT", "1", 1);
    // The pvmd learns the host file's per-host options, but every host line is marked '&' (do
    // not start it): the master adds the hosts itself with pvm_addhosts, which says which
    // host failed and why, instead of a pvmd that drops it silently in the background.
    std::string options_file;
    if (!hostfile.empty()) {
        std::string text, lines;
        if (!read_text(hostfile, text, err))
            return false;
        std::string self = name.empty() ? host_name() : name;
        size_t pos = 0;
        while (pos < text.size()) {
            size_t nl = text.find('\n', pos);
            std::string line = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
            pos = nl == std::string::npos ? text.size() : nl + 1;
            char host[512];
            bool entry = sscanf(line.c_str(), " %511s", host) == 1 && host[0] != '#' &&
                         host[0] != '*' && host[0] != '&';
            // The master's own line stays: the pvmd takes its options from it.
            lines += (entry && self != host ? "&" : "") + trim(line) + "\n";
        }
        options_file = tmpdir_ + "/hostfile";
        if (!write_text(options_file, lines, err))
            return false;
    }
    std::string program = pvmd_program();
    if (!is_executable(program)) {
        err = "cannot find the PVM daemon (" + program + "): install the pvm package";
        return false;
    }
    int out[2];
    if (pipe2(out, O_CLOEXEC) != 0)
        return sys_fail(err, "pipe2");
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0)
        return sys_fail(err, "fork");
    if (pid == 0) {
        // The pvmd halts (killing its tasks) if the master dies, even by SIGKILL.
        prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() != parent)
            _exit(127);
        setpgid(0, 0);   // Ctrl-C reaches the master only; it halts the pvmd cleanly
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, nullptr);
        dup2(out[1], 1);
        std::string errlog = tmpdir_ + "/pvmd.stderr";
        int e = open(errlog.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (e >= 0)
            dup2(e, 2);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0)
            dup2(devnull, 0);
        if (chdir("/") != 0)
            _exit(126);
        // In every task it spawns, the pvmd closes each descriptor up to the soft limit, one
        // close() apiece: 40,000 calls for two slaves under this machine's 20,000, and about
        // 0.2 s a slave under the 1,048,576 many containers set. PVM waits with select(),
        // which cannot use a descriptor past FD_SETSIZE anyway: the daemon and its tasks
        // (the slaves, their renderers) get at most that.
        struct rlimit files;
        if (getrlimit(RLIMIT_NOFILE, &files) == 0 && files.rlim_cur > FD_SETSIZE) {
            files.rlim_cur = FD_SETSIZE;
            setrlimit(RLIMIT_NOFILE, &files);
        }
        std::vector<std::string> args = {program};
        if (!name.empty())
            args.push_back("-n" + name);
        if (!options_file.empty())
            args.push_back(options_file);
        std::vector<char *> av;
        for (std::string &a : args)
            av.push_back(&a[0]);
        av.push_back(nullptr);
        execv(program.c_str(), av.data());
        dprintf(2, "exec %s: %s\n", program.c_str(), strerror(errno));
        _exit(127);
    }
    close(out[1]);
    pvmd_pid_ = pid;
    embedded_ = true;
    // Ended by the watchdog, the master takes its pvmd along (its tasks here with it).
    watchdog::kill_with_me(pid);
    watchdog::set_pvm_hint(strf("the private PVM daemon (pid %d) does not answer", int(pid)));

    // The pvmd prints its socket name on stdout once it is ready.
    std::string line;
    double deadline = now() + timeout;
    bool ready = false;
    while (!ready && !watchdog::stop_requested()) {
        int left = int((deadline - now()) * 1000);
        if (left <= 0)
            break;
        struct pollfd p = {out[0], POLLIN, 0};
        if (poll(&p, 1, std::min(left, 100)) <= 0)
            continue;
        char c;
        ssize_t n = read(out[0], &c, 1);
        if (n <= 0)
            break;
        if (c == '\n')
            ready = true;
        else
            line += c;
    }
    close(out[0]);
    if (!ready) {
        std::string log;
        FILE *f = fopen((tmpdir_ + "/pvmd.stderr").c_str(), "r");
        if (f) {
            char buf[512];
            while (fgets(buf, sizeof buf, f))
                log += buf;
            fclose(f);
        }
        err = strf("the private pvmd (%s) did not start within %.0f s", program.c_str(), timeout);
        if (!log.empty())
            err += ":\n" + log;
        stop();
        return false;
    }
    {
        watchdog::Guard guard("pvm_mytid", watchdog::kLocalPvmBound);
        mytid_ = pvm_mytid();
    }
    if (mytid_ < 0) {
        err = "pvm_mytid after starting a private pvmd: " + pvm_error(mytid_);
        stop();
        return false;
    }
    return true;
}

void VirtualMachine::stop()
{
    if (!embedded_) {
        if (mytid_ >= 0) {
            watchdog::Guard guard("pvm_exit", watchdog::kLocalPvmBound);
            pvm_exit();
        }
        mytid_ = -1;
        return;
    }
    // A stopped private pvmd would never halt: it is killed below.
    if (mytid_ >= 0 && pvmd_pid_ > 0 && process_stopped(int(pvmd_pid_)))
        mytid_ = -1;
    if (mytid_ >= 0) {
        // pvm_halt() also signals its caller with SIGTERM: ignore it for the moment.
        struct sigaction ign, old;
        memset(&ign, 0, sizeof ign);
        ign.sa_handler = SIG_IGN;
        sigaction(SIGTERM, &ign, &old);
        {
            watchdog::Guard guard("pvm_halt", watchdog::kLocalPvmBound);
            pvm_halt();
        }
        mytid_ = -1;
        if (pvmd_pid_ > 0) {
            double deadline = now() + 5;
            int status;
            while (waitpid(pvmd_pid_, &status, WNOHANG) == 0 && now() < deadline)
                usleep(10000);
        }
        sigaction(SIGTERM, &old, nullptr);
    }
    if (pvmd_pid_ > 0) {
        // Still there (halt failed or pvmd never enrolled us): stop it the hard way.
        if (kill(pvmd_pid_, 0) == 0) {
            kill(pvmd_pid_, SIGTERM);
            double deadline = now() + 3;
            int status;
            while (waitpid(pvmd_pid_, &status, WNOHANG) == 0 && now() < deadline)
                usleep(10000);
            if (kill(pvmd_pid_, 0) == 0) {
                kill(pvmd_pid_, SIGKILL);
                waitpid(pvmd_pid_, &status, 0);
            }
        }
        pvmd_pid_ = -1;
        watchdog::kill_with_me(-1);
    }
    if (!tmpdir_.empty()) {
        remove_tree(tmpdir_);
        tmpdir_.clear();
    }
    embedded_ = false;
}

} // namespace fc
