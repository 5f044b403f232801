// child_process.cpp - child processes and their output (see child_process.h).
#include "child_process.h"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "clock.h"
#include "files.h"
#include "text.h"

namespace fc {

void LineSplitter::feed(const char *data, size_t n, std::vector<std::string> &out)
{
    for (size_t i = 0; i < n; i++) {
        char c = data[i];
        if (c == '\n' || c == '\r') {
            if (!partial_.empty())
                out.push_back(partial_);
            partial_.clear();
        } else {
            partial_ += c;
        }
    }
}

std::string LineSplitter::rest()
{
    std::string r;
    r.swap(partial_);
    return r;
}

bool start_child(const std::vector<std::string> &argv, const std::string &cwd, int nice_inc,
                 Child &child, std::string &err, const std::vector<std::pair<int, int>> &extra,
                 bool batch)
{
    // Everything the child needs is prepared here: after fork() the child of a threaded
    // process may only make async-signal-safe calls (no allocation).
    std::vector<char *> av;
    for (const std::string &a : argv)
        av.push_back(const_cast<char *>(a.c_str()));
    av.push_back(nullptr);
    const size_t kMaxExtra = 8;
    int targets[kMaxExtra], sources[kMaxExtra];
    size_t nextra = std::min(extra.size(), kMaxExtra);
    for (size_t i = 0; i < nextra; i++) {
        targets[i] = extra[i].first;
        sources[i] = extra[i].second;
    }
    const std::string cd_failed = "fc: cannot enter directory " + cwd + "\n";
    const std::string exec_failed = "fc: cannot run " + argv[0] + " (missing or not executable)\n";
    int out[2];
    if (pipe2(out, O_CLOEXEC) != 0)
        return sys_fail(err, "pipe2");
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        close(out[0]);
        close(out[1]);
        return sys_fail(err, "fork");
    }
    if (pid == 0) {
        // Die with the parent: a killed slave must not leave a renderer running.
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent)
            _exit(127);
        setpgid(0, 0);
        signal(SIGPIPE, SIG_DFL);
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, nullptr);
        // Move the inherited descriptors out of the way first: a source may sit on a number
        // another one is mapped to.
        for (size_t i = 0; i < nextra; i++)
            if ((sources[i] = fcntl(sources[i], F_DUPFD_CLOEXEC, 100)) < 0)
                _exit(126);
        for (size_t i = 0; i < nextra; i++)
            if (dup2(sources[i], targets[i]) < 0)
                _exit(126);
        dup2(out[1], 1);
        dup2(out[1], 2);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0)
            dup2(devnull, 0);
        if (nice_inc > 0)
            setpriority(PRIO_PROCESS, 0, nice_inc);
        if (batch) {
            // Best effort (no privilege needed): a failure leaves the usual policy.
            struct sched_param none;
            memset(&none, 0, sizeof none);
            sched_setscheduler(0, SCHED_BATCH, &none);
        }
        if (!cwd.empty() && chdir(cwd.c_str()) != 0) {
            ssize_t w = write(2, cd_failed.data(), cd_failed.size());
            (void)w;
            _exit(126);
        }
        execv(av[0], av.data());
        ssize_t w = write(2, exec_failed.data(), exec_failed.size());
        (void)w;
        _exit(127);
    }
    close(out[1]);
    fcntl(out[0], F_SETFL, fcntl(out[0], F_GETFL) | O_NONBLOCK);
    child.pid = pid;
    child.fd = out[0];
    return true;
}

bool read_child(Child &child, std::vector<std::string> &lines)
{
    if (child.fd < 0)
        return false;
    char buf[8192];
    for (;;) {
        ssize_t n = read(child.fd, buf, sizeof buf);
        if (n > 0) {
            child.lines.feed(buf, size_t(n), lines);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return true;
        // EOF or hard error: flush the last partial line.
        std::string rest = child.lines.rest();
        if (!rest.empty())
            lines.push_back(rest);
        close(child.fd);
        child.fd = -1;
        return false;
    }
}

void kill_child(Child &child)
{
    if (child.pid > 0) {
        kill(-child.pid, SIGKILL);
        kill(child.pid, SIGKILL);
        int status;
        while (waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
        }
        child.pid = -1;
    }
    if (child.fd >= 0) {
        close(child.fd);
        child.fd = -1;
    }
}

bool wait_child(Child &child, double timeout, int &status)
{
    if (child.pid <= 0)
        return false;
    double deadline = now() + timeout;
    // Callers mostly wait for a process that closed its output and is exiting: it is gone
    // within a fraction of a millisecond, so poll soon and back off (a flat 5 ms sleep cost
    // every probe of POV-Ray 5 ms of fc-master's start).
    useconds_t pause = 100;
    for (;;) {
        pid_t r = waitpid(child.pid, &status, WNOHANG);
        if (r == child.pid) {
            child.pid = -1;
            return true;
        }
        if (r < 0 && errno != EINTR)
            return false;
        if (now() >= deadline)
            return false;
        usleep(pause);
        pause = std::min<useconds_t>(pause * 2, 5000);
    }
}

std::string describe_status(int status)
{
    if (WIFEXITED(status))
        return strf("exit status %d", WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return strf("killed by signal %d (%s)", WTERMSIG(status), strsignal(WTERMSIG(status)));
    return strf("wait status %d", status);
}

} // namespace fc
