// child_process.h - child processes whose output we read: POV-Ray's probes and renderers,
// fc-image-writer. Each child gets its own process group, dies with the thread that started
// it, and has its stdout and stderr on one non-blocking pipe, read line by line.
#pragma once

#include <sys/types.h>

#include <string>
#include <utility>
#include <vector>

namespace fc {

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

} // namespace fc
