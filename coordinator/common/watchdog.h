// watchdog.h - fc-master never hangs: PVM's calls cannot be interrupted (libpvm waits on its
// daemon's socket and retries), so a thread of its own watches the main thread's calls that
// may block and the stop signals.
//
// A call that may block runs under a Guard with a bound and a description of what to do: past
// the bound, the watchdog says so (the call, the bound, what to do) and ends the process with
// exit status 1. A stop signal (SIGINT, SIGTERM, SIGHUP) asks the main thread to stop, which
// it does where it looks (stop_requested); should it not be done within kGrace seconds (it is
// inside a call that blocks, or has more to do than that), the watchdog ends the process
// itself with 128 + the signal. Either way it first kills what was registered to die with it
// (a private pvmd: killed, it takes its tasks on this host along), and a killed process
// leaves the output directory as consistent as any kill does: complete frames under final
// names, the run's record, temporary files a resume removes.
//
// Without start() (fc-slave) Guards and stop_requested() cost nothing and do nothing.
#pragma once

#include <sys/types.h>

#include <string>

namespace fc {
namespace watchdog {

const double kGrace = 0.7;      // seconds a stop signal leaves the main thread to stop
                                // (the process must end within a second)

// Start the thread and route the stop signals to it (call once, from main, before other
// threads). prog names the program in its messages ("fc-master").
void start(const char *prog);

// The stop signal received (0: none).
int stop_requested();

// Processes to SIGKILL when the watchdog ends the process (a private pvmd); pid <= 0 forgets.
void kill_with_me(pid_t pid);

// What to do when a PVM call does not return (set once the virtual machine is known).
void set_pvm_hint(const std::string &hint);
const std::string &pvm_hint();

class Guard {
public:
    // The main thread enters a call that may block: `call` names it ("pvm_spawn on fch2"),
    // `hint` says what to do when it does not return within `bound` seconds (empty: the PVM
    // hint). Guards nest: the innermost counts.
    Guard(const std::string &call, double bound, const std::string &hint = std::string());
    ~Guard();
    Guard(const Guard &) = delete;
    Guard &operator=(const Guard &) = delete;

private:
    bool armed_ = false;
};

// The bound of PVM calls that talk only to this host's pvmd.
const double kLocalPvmBound = 10.0;

} // namespace watchdog
} // namespace fc
