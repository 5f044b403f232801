// util.h - small helpers shared by fc-master and fc-slave: formatting, time, files, child processes.
//
// One error convention everywhere: a function that can fail returns bool (true = OK) and
// fills a caller-owned std::string with a message that names the failing call and, for
// system calls, strerror(errno).
#pragma once

#include <sys/types.h>

#include <cstdarg>
#include <cstdint>
#include <string>
#include <vector>

namespace fc {

// printf into a std::string.
std::string strf(const char *format, ...) __attribute__((format(printf, 1, 2)));

// Fill err with "<call>: <strerror(errno)>" and return false.
bool sys_fail(std::string &err, const std::string &call);

// Seconds since an arbitrary fixed point (CLOCK_MONOTONIC).
double now();

// This machine's host name (gethostname), and its number of online CPUs (>= 1).
std::string host_name();
int cpu_count();

// Absolute path of the running executable's directory (from /proc/self/exe).
std::string self_dir();

// Directory that holds path ("." when none), and the last component of path.
std::string dir_name(const std::string &path);
std::string base_name(const std::string &path);

bool file_exists(const std::string &path);
bool is_executable(const std::string &path);

// Search PATH for an executable; returns "" when not found. Absolute names are checked as is.
std::string which(const std::string &name);

// Create a fresh private directory "<parent>/<prefix>XXXXXX"; on success dir holds its path.
bool make_temp_dir(const std::string &parent, const std::string &prefix, std::string &dir,
                   std::string &err);

// Remove a directory tree (no symlinks followed). Errors are ignored: used for cleanup.
void remove_tree(const std::string &path);

// Remove directories "<parent>/<prefix><pid>-*" owned by us whose process <pid> is gone
// (left behind by a killed fc-master or fc-slave).
void remove_stale_dirs(const std::string &parent, const std::string &prefix);

// Create dir and its missing parents; false with err (strerror) unless dir is a directory.
bool make_dirs(const std::string &dir, std::string &err);

// Write text to path (truncating). Returns false with err on failure.
bool write_text(const std::string &path, const std::string &text, std::string &err);

// Write bytes to path (created or truncated, mode 0644) and make them durable: every write,
// the fsync and the close are checked, and the file's size on disk must equal the bytes. On
// failure the file is removed and err names the call and errno's text ("No space left on
// device" for a full disk).
bool write_file_durably(const std::string &path, const void *data, size_t size, std::string &err);

// fsync a directory, so that a rename in it survives a crash.
bool sync_dir(const std::string &dir, std::string &err);

// Bytes available to us on the file system holding path; false with err.
bool free_bytes(const std::string &path, unsigned long long &bytes, std::string &err);

// "230 KB", "10.4 MB": a size for people.
std::string human_bytes(double bytes);

// A 64-bit FNV-1a hash of bytes (stable across versions and machines: it goes into files).
uint64_t hash_bytes(const void *data, size_t size, uint64_t seed = 14695981039346656037ull);

// A 64-bit hash of bytes taken eight at a time (little-endian words; stable across versions
// and machines too): for frames' pixels, where FNV-1a's byte at a time cost fc-master 0.4 ms
// a 320x240 frame.
uint64_t hash_words(const void *data, size_t size);

// Read a whole file into text; false with err.
bool read_text(const std::string &path, std::string &text, std::string &err);

// Split text into physical lines on '\n' and '\r' (POV-Ray rewrites progress lines with '\r').
class LineSplitter {
public:
    // Feed raw bytes; complete lines are appended to out (without terminators, empty lines dropped).
    void feed(const char *data, size_t n, std::vector<std::string> &out);
    // Return any unterminated rest (at end of stream).
    std::string rest();
private:
    std::string partial_;
};

// A child process whose stdout and stderr go to one pipe we read.
struct Child {
    pid_t pid = -1;
    int fd = -1;        // read end of the output pipe; -1 after EOF
    LineSplitter lines;
};

// Tell glibc's allocator to keep freed memory for the next allocation instead of giving it
// back to the kernel. A coordinator's buffers are frame-sized and come and go every frame;
// by default glibc unmapped or trimmed each at its free (its thresholds follow the largest
// block freed) and the next frame faulted every page in again: at 1280x960 two thirds of
// fc-master's CPU. What is kept is bounded by the frames in flight, which the process holds
// at its peak anyway.
void keep_freed_memory();

// Start argv[0] (absolute path) in directory cwd with stdout+stderr on a pipe. The child gets
// its own process group and is killed (SIGKILL) when the thread that started it ends
// (PR_SET_PDEATHSIG follows the thread, not the process: start long-lived children from the
// main thread). nice_inc > 0 lowers its priority; batch runs it under SCHED_BATCH (its
// wake-ups do not preempt). fds maps descriptors of ours (second) to the numbers the child
// sees them under (first, >= 3). Returns false with err if fork/pipe fails; exec failure
// shows up as exit status 127 with a message on the pipe.
bool start_child(const std::vector<std::string> &argv, const std::string &cwd, int nice_inc,
                 Child &child, std::string &err,
                 const std::vector<std::pair<int, int>> &fds = {}, bool batch = false);

// Read what is available from child.fd into lines (non-blocking); closes fd at EOF.
// Returns false at EOF.
bool read_child(Child &child, std::vector<std::string> &lines);

// Kill the child's process group (SIGKILL) and reap it; safe to call twice.
void kill_child(Child &child);

// Wait up to timeout seconds for the child to exit; returns true and its wait status on exit.
bool wait_child(Child &child, double timeout, int &status);

// Describe a wait status: "exit status 1", "killed by signal 9 (Killed)".
std::string describe_status(int status);

// Append one line to the file named by $FC_DEBUG_LOG (if set): a trace of the protocol for
// diagnosing runs, shared by the master and all slaves of a machine.
void debug_log(const char *format, ...) __attribute__((format(printf, 1, 2)));

// Trim spaces at both ends.
std::string trim(const std::string &s);

// Routes SIGINT, SIGTERM and SIGHUP to `handler` and ignores SIGPIPE (a dead peer's pipe
// must give EPIPE, not kill the process).
void install_signal_handlers(void (*handler)(int));
bool starts_with(const std::string &s, const std::string &prefix);
bool ends_with(const std::string &s, const std::string &suffix);

} // namespace fc
