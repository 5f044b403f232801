// util.cpp - small helpers shared by fc-master and fc-slave.
#include "util.h"

#include <dirent.h>
#include <endian.h>
#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace fc {

std::string strf(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    char small[512];
    va_list ap2;
    va_copy(ap2, ap);
    int n = vsnprintf(small, sizeof small, format, ap);
    va_end(ap);
    if (n < 0) {
        va_end(ap2);
        return std::string();
    }
    if (size_t(n) < sizeof small) {
        va_end(ap2);
        return std::string(small, size_t(n));
    }
    std::string out(size_t(n) + 1, '\0');
    vsnprintf(&out[0], out.size(), format, ap2);
    va_end(ap2);
    out.resize(size_t(n));
    return out;
}

bool sys_fail(std::string &err, const std::string &call)
{
    err = call + ": " + strerror(errno);
    return false;
}

double now()
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

std::string host_name()
{
    char buf[256];
    if (gethostname(buf, sizeof buf - 1) != 0)
        return "localhost";
    buf[sizeof buf - 1] = '\0';
    return buf;
}

int cpu_count()
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : int(n);
}

std::string self_dir()
{
    char buf[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0)
        return ".";
    buf[n] = '\0';
    return dir_name(buf);
}

std::string dir_name(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos)
        return ".";
    if (slash == 0)
        return "/";
    return path.substr(0, slash);
}

std::string base_name(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool file_exists(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

bool is_executable(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
}

std::string which(const std::string &name)
{
    if (name.find('/') != std::string::npos)
        return is_executable(name) ? name : std::string();
    const char *path = getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        size_t end = dirs.find(':', start);
        if (end == std::string::npos)
            end = dirs.size();
        std::string dir = dirs.substr(start, end - start);
        if (!dir.empty()) {
            std::string cand = dir + "/" + name;
            if (is_executable(cand))
                return cand;
        }
        start = end + 1;
    }
    return std::string();
}

bool make_temp_dir(const std::string &parent, const std::string &prefix, std::string &dir,
                   std::string &err)
{
    std::string templ = parent + "/" + prefix + "XXXXXX";
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data()))
        return sys_fail(err, "mkdtemp " + templ);
    dir = buf.data();
    return true;
}

void remove_tree(const std::string &path)
{
    struct stat st;
    if (lstat(path.c_str(), &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        if (DIR *d = opendir(path.c_str())) {
            while (struct dirent *e = readdir(d)) {
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                    continue;
                remove_tree(path + "/" + e->d_name);
            }
            closedir(d);
        }
        rmdir(path.c_str());
    } else {
        unlink(path.c_str());
    }
}

void remove_stale_dirs(const std::string &parent, const std::string &prefix)
{
    DIR *d = opendir(parent.c_str());
    if (!d)
        return;
    while (struct dirent *e = readdir(d)) {
        std::string name = e->d_name;
        if (!starts_with(name, prefix))
            continue;
        int pid = atoi(name.c_str() + prefix.size());
        if (pid <= 0 || name.find('-', prefix.size()) == std::string::npos)
            continue;
        std::string path = parent + "/" + name;
        struct stat st;
        if (lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != getuid())
            continue;
        if (kill(pid, 0) == 0 || errno == EPERM)
            continue;   // still running
        remove_tree(path);
    }
    closedir(d);
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

bool write_text(const std::string &path, const std::string &text, std::string &err)
{
    FILE *f = fopen(path.c_str(), "w");
    if (!f)
        return sys_fail(err, "fopen " + path);
    bool ok = fwrite(text.data(), 1, text.size(), f) == text.size();
    if (fclose(f) != 0)
        ok = false;
    if (!ok)
        return sys_fail(err, "write " + path);
    return true;
}

bool write_file_durably(const std::string &path, const void *data, size_t size, std::string &err)
{
    int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        return sys_fail(err, "open " + path);
    const char *p = static_cast<const char *>(data);
    size_t left = size;
    bool ok = true;
    std::string call;
    while (left > 0) {
        ssize_t n = write(fd, p, left);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (n == 0)
                errno = ENOSPC;     // a write that makes no progress: nothing fits any more
            ok = false;
            call = "write " + path;
            break;
        }
        p += n;
        left -= size_t(n);
    }
    // A full disk may only show at fsync (delayed allocation) or close (network file systems).
    if (ok && fsync(fd) != 0) {
        ok = false;
        call = "fsync " + path;
    }
    struct stat st;
    if (ok && fstat(fd, &st) != 0) {
        ok = false;
        call = "fstat " + path;
    }
    if (ok && st.st_size != off_t(size)) {
        errno = EIO;
        err = strf("%s has %lld bytes on disk, %zu were written", path.c_str(),
                   (long long)st.st_size, size);
        close(fd);
        unlink(path.c_str());
        return false;
    }
    int saved = errno;
    if (close(fd) != 0 && ok) {
        ok = false;
        call = "close " + path;
        saved = errno;
    }
    if (!ok) {
        errno = saved;
        sys_fail(err, call);
        unlink(path.c_str());
        errno = saved;
        return false;
    }
    return true;
}

bool sync_dir(const std::string &dir, std::string &err)
{
    int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return sys_fail(err, "open " + dir);
    // Some file systems cannot sync a directory (EINVAL): the rename is as durable as they get.
    bool ok = fsync(fd) == 0 || errno == EINVAL;
    int saved = errno;
    close(fd);
    errno = saved;
    return ok || sys_fail(err, "fsync " + dir);
}

bool free_bytes(const std::string &path, unsigned long long &bytes, std::string &err)
{
    struct statvfs sv;
    if (statvfs(path.c_str(), &sv) != 0)
        return sys_fail(err, "statvfs " + path);
    bytes = (unsigned long long)sv.f_bavail * (unsigned long long)sv.f_frsize;
    return true;
}

std::string human_bytes(double b)
{
    if (b < 1024)
        return strf("%.0f bytes", b);
    if (b < 1024.0 * 1024)
        return strf("%.0f KB", b / 1024);
    if (b < 1024.0 * 1024 * 1024)
        return strf("%.1f MB", b / (1024.0 * 1024));
    return strf("%.2f GB", b / (1024.0 * 1024 * 1024));
}

uint64_t hash_bytes(const void *data, size_t size, uint64_t h)
{
    const unsigned char *p = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < size; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

uint64_t hash_words(const void *data, size_t size)
{
    const unsigned char *p = static_cast<const unsigned char *>(data);
    auto mix = [](uint64_t h, uint64_t word) {
        h ^= word;
        h *= 0x9e3779b97f4a7c15ull;
        return h ^ (h >> 32);
    };
    uint64_t h = mix(0x6672616d65730000ull, uint64_t(size));   // "frames", then the length
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        // The eight bytes as a little-endian word on every machine: one load (GCC compiled
        // the byte-by-byte composition into a loop of eight loads and shifts per word).
        uint64_t word;
        memcpy(&word, p + i, sizeof word);
        h = mix(h, le64toh(word));
    }
    // The last size % 8 bytes, zero-padded: the length, mixed first, tells the padding from
    // zero bytes.
    uint64_t tail = 0;
    for (size_t b = size; b > i; b--)
        tail = (tail << 8) | p[b - 1];
    return mix(h, tail);
}

bool read_text(const std::string &path, std::string &text, std::string &err)
{
    FILE *f = fopen(path.c_str(), "r");
    if (!f)
        return sys_fail(err, "fopen " + path);
    text.clear();
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        text.append(buf, n);
    bool bad = ferror(f) != 0;
    fclose(f);
    if (bad)
        return sys_fail(err, "read " + path);
    return true;
}

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

void keep_freed_memory()
{
    // 32 MiB is the largest mmap threshold glibc accepts: blocks up to it come from the heap.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
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

void debug_log(const char *format, ...)
{
    static int fd = -2;
    if (fd == -2) {
        const char *path = getenv("FC_DEBUG_LOG");
        fd = (path && *path) ? open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
    }
    if (fd < 0)
        return;
    va_list ap;
    va_start(ap, format);
    char msg[1024];
    vsnprintf(msg, sizeof msg, format, ap);
    va_end(ap);
    static std::string prog;
    if (prog.empty()) {
        char buf[256] = {0};
        ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
        prog = n > 0 ? base_name(std::string(buf, size_t(n))) : "fc";
    }
    std::string line = strf("%.3f %s[%d] %s\n", now(), prog.c_str(), int(getpid()), msg);
    ssize_t w = write(fd, line.data(), line.size());
    (void)w;
}

std::string trim(const std::string &s)
{
    size_t a = s.find_first_not_of(" \t");
    if (a == std::string::npos)
        return std::string();
    size_t b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

bool starts_with(const std::string &s, const std::string &prefix)
{
    return s.compare(0, prefix.size(), prefix) == 0;
}

bool ends_with(const std::string &s, const std::string &suffix)
{
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void install_signal_handlers(void (*handler)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = handler;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    sigaction(SIGHUP, &sa, nullptr);
    signal(SIGPIPE, SIG_IGN);
}

} // namespace fc
