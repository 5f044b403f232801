// watchdog.cpp - the thread that keeps fc-master from hanging (see watchdog.h).
#include "watchdog.h"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "clock.h"
#include "signals.h"
#include "text.h"

namespace fc {
namespace watchdog {

namespace {

std::atomic<bool> g_started{false};
volatile sig_atomic_t g_signal = 0;
std::atomic<double> g_signal_time{0};
const char *g_prog = "fc";

std::mutex g_mutex;                     // guards the fields below
struct Call {
    std::string what, hint;
    double deadline;
};
std::vector<Call> g_calls;              // the guarded calls, innermost last
std::vector<pid_t> g_kill;
std::string g_pvm_hint;

void on_stop_signal(int sig)
{
    if (!g_signal) {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        g_signal_time = double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
        g_signal = sig;
    }
}

// End the process now: what was registered dies with it; stderr gets one message.
[[noreturn]] void end_now(const std::string &message, int status)
{
    std::string line = strf("%s: %s\n", g_prog, message.c_str());
    ssize_t w = write(2, line.data(), line.size());
    (void)w;
    for (pid_t pid : g_kill)
        if (pid > 0)
            kill(pid, SIGKILL);
    _exit(status);
}

void watch()
{
    for (;;) {
        usleep(50000);
        double t = now();
        std::lock_guard<std::mutex> lock(g_mutex);
        if (g_signal && t - g_signal_time > kGrace) {
            std::string inside = g_calls.empty() ? std::string()
                                                 : " (it waited in " + g_calls.back().what + ")";
            end_now(strf("interrupted (%s), and not stopped within %.1f s%s: ending at once",
                         strsignal(g_signal), kGrace, inside.c_str()),
                    128 + g_signal);
        }
        if (!g_calls.empty() && t > g_calls.back().deadline) {
            const Call &c = g_calls.back();
            const std::string &hint = c.hint.empty() ? g_pvm_hint : c.hint;
            end_now(c.what + " did not return" + (hint.empty() ? "" : ": " + hint), 1);
        }
    }
}

} // namespace

void start(const char *prog)
{
    if (g_started.exchange(true))
        return;
    g_prog = prog;
    install_signal_handlers(on_stop_signal);
    std::thread(watch).detach();
}

int stop_requested()
{
    return g_signal;
}

void kill_with_me(pid_t pid)
{
    std::lock_guard<std::mutex> lock(g_mutex);
    g_kill.clear();
    if (pid > 0)
        g_kill.push_back(pid);
}

void set_pvm_hint(const std::string &hint)
{
    std::lock_guard<std::mutex> lock(g_mutex);
    g_pvm_hint = hint;
}

const std::string &pvm_hint()
{
    return g_pvm_hint;
}

Guard::Guard(const std::string &call, double bound, const std::string &hint)
{
    if (!g_started)
        return;
    std::lock_guard<std::mutex> lock(g_mutex);
    g_calls.push_back({strf("%s (within %.0f s)", call.c_str(), bound), hint, now() + bound});
    armed_ = true;
}

Guard::~Guard()
{
    if (!armed_)
        return;
    std::lock_guard<std::mutex> lock(g_mutex);
    g_calls.pop_back();
}

} // namespace watchdog
} // namespace fc
