// pvmutil.cpp - join or start a PVM virtual machine (see pvmutil.h), PVM error names.
#include "pvmutil.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <pvm3.h>

#include "util.h"

namespace fc {

std::string pvm_error(int code)
{
    static const struct { int code; const char *name, *text; } table[] = {
        {PvmBadParam, "PvmBadParam", "bad parameter"},
        {PvmMismatch, "PvmMismatch", "parameter mismatch"},
        {PvmOverflow, "PvmOverflow", "value too large"},
        {PvmNoData, "PvmNoData", "end of buffer"},
        {PvmNoHost, "PvmNoHost", "no such host"},
        {PvmNoFile, "PvmNoFile", "no such file"},
        {PvmDenied, "PvmDenied", "permission denied"},
        {PvmNoMem, "PvmNoMem", "malloc failed"},
        {PvmBadMsg, "PvmBadMsg", "can't decode message"},
        {PvmSysErr, "PvmSysErr", "can't contact local daemon"},
        {PvmNoBuf, "PvmNoBuf", "no current buffer"},
        {PvmNoSuchBuf, "PvmNoSuchBuf", "no such buffer"},
        {PvmHostFail, "PvmHostFail", "host failed"},
        {PvmNoParent, "PvmNoParent", "no parent task"},
        {PvmNotImpl, "PvmNotImpl", "not implemented"},
        {PvmDSysErr, "PvmDSysErr", "pvmd system error"},
        {PvmBadVersion, "PvmBadVersion", "version mismatch"},
        {PvmOutOfRes, "PvmOutOfRes", "out of resources"},
        {PvmDupHost, "PvmDupHost", "duplicate host"},
        {PvmCantStart, "PvmCantStart", "can't start pvmd"},
        {PvmAlready, "PvmAlready", "already in progress"},
        {PvmNoTask, "PvmNoTask", "no such task"},
        {PvmNotFound, "PvmNotFound", "not found"},
        {PvmExists, "PvmExists", "already exists"},
        {PvmHostrNMstr, "PvmHostrNMstr", "hoster run on non-master host"},
        {PvmParentNotSet, "PvmParentNotSet", "spawning parent set PvmNoSpawnParent"},
        {PvmIPLoopback, "PvmIPLoopback", "master host's IP is loopback"},
    };
    for (auto &e : table)
        if (e.code == code)
            return strf("%s (%s)", e.name, e.text);
    return strf("PVM error %d", code);
}

namespace {

// Is a pvmd listening behind this PVM_TMP? pvmd.<uid> names its Unix socket; try connecting,
// so a file left behind by a killed pvmd is not mistaken for a running machine (libpvm would
// print errors and fail).
bool pvmd_alive(const std::string &pvm_tmp)
{
    std::string file = pvm_tmp + strf("/pvmd.%d", int(getuid()));
    FILE *f = fopen(file.c_str(), "r");
    if (!f)
        return false;
    char buf[512] = {0};
    bool got = fgets(buf, sizeof buf, f) != nullptr;
    fclose(f);
    if (!got)
        return false;
    std::string addr = trim(std::string(buf, strcspn(buf, "\r\n")));
    if (addr.empty() || addr[0] != '/')
        return true;    // a TCP address: let libpvm try it
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
    remove_stale_dirs("/tmp", kPrivatePrefix);
}

bool VirtualMachine::start(bool force_private, const std::string &hostfile,
                           const std::string &name, double timeout, std::string &err)
{
    pvm_setopt(PvmAutoErr, 0);
    if (!force_private) {
        const char *t = getenv("PVM_TMP");
        std::string pvm_tmp = (t && *t) ? t : "/tmp";
        if (pvmd_alive(pvm_tmp)) {
            if (geteuid() == 0 && !getenv("PVM_ALLOW_ROOT"))
                setenv("PVM_ALLOW_ROOT", "1", 1);
            mytid_ = pvm_mytid();
            if (mytid_ < 0) {
                err = "cannot join the running virtual machine (PVM_TMP=" + pvm_tmp +
                      "): pvm_mytid: " + pvm_error(mytid_);
                return false;
            }
            embedded_ = false;
            if (!hostfile.empty()) {
                // Add the listed hosts to the running machine (per-host options are not
                // interpreted here; start the machine with the hostfile to use them).
                FILE *f = fopen(hostfile.c_str(), "r");
                if (!f)
                    return sys_fail(err, "fopen " + hostfile);
                char line[1024];
                while (fgets(line, sizeof line, f)) {
                    char name[512];
                    if (sscanf(line, " %511s", name) != 1 || name[0] == '#' || name[0] == '*' ||
                        name[0] == '&')
                        continue;
                    char *names[1] = {name};
                    int info = 0;
                    int n = pvm_addhosts(names, 1, &info);
                    if (n < 1 && info != PvmDupHost)
                        fprintf(stderr, "fc-master: warning: cannot add host %s: %s\n", name,
                                pvm_error(info).c_str());
                }
                fclose(f);
            }
            return true;
        }
    }
    return start_private(hostfile, name, timeout, err);
}

bool VirtualMachine::start_private(const std::string &hostfile, const std::string &name,
                                   double timeout, std::string &err)
{
    remove_stale_private_vms();
    if (!make_temp_dir("/tmp", strf("%s%d-", kPrivatePrefix, int(getpid())), tmpdir_, err))
        return false;
    // Every program of this virtual machine (pvmd, master, slaves) must see the same PVM_TMP;
    // slaves inherit the pvmd's environment.
    setenv("PVM_TMP", tmpdir_.c_str(), 1);
    if (geteuid() == 0)
        setenv("PVM_ALLOW_ROOT", "1", 1);
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
        std::vector<std::string> args = {program};
        if (!name.empty())
            args.push_back("-n" + name);
        if (!hostfile.empty())
            args.push_back(hostfile);
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

    // The pvmd prints its socket name on stdout once it is ready.
    std::string line;
    double deadline = now() + timeout;
    bool ready = false;
    while (!ready) {
        int left = int((deadline - now()) * 1000);
        if (left <= 0)
            break;
        struct pollfd p = {out[0], POLLIN, 0};
        if (poll(&p, 1, left) <= 0)
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
    mytid_ = pvm_mytid();
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
        if (mytid_ >= 0)
            pvm_exit();
        mytid_ = -1;
        return;
    }
    if (mytid_ >= 0) {
        // pvm_halt() also signals its caller with SIGTERM: ignore it for the moment.
        struct sigaction ign, old;
        memset(&ign, 0, sizeof ign);
        ign.sa_handler = SIG_IGN;
        sigaction(SIGTERM, &ign, &old);
        pvm_halt();
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
    }
    if (!tmpdir_.empty()) {
        remove_tree(tmpdir_);
        tmpdir_.clear();
    }
    embedded_ = false;
}

} // namespace fc
