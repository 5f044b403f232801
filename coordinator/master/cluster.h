// cluster.h - the virtual machine fc-master renders on: its hosts and the slaves on them.
//
// Joins the user's running PVM virtual machine or starts a private one (virtual_machine.h), watches
// hosts (pvm_notify PvmHostDelete / PvmHostAdd) and slaves (PvmTaskExit), spawns one slave
// per core of each host (learned from the host's first FC_HELLO), replaces slaves that exit
// (a few times per host) and leaves out hosts whose slaves keep failing.
#pragma once

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "virtual_machine.h"

namespace fc {

enum class SlaveState { Starting, Ready, Gone };

struct SlaveInfo {
    int tid = 0;
    int dtid = 0;               // its host's pvmd
    std::string host;
    SlaveState state = SlaveState::Starting;
    double spawned = 0, last_msg = 0, last_ping = 0;
    double last_given = 0;      // when it was last sent work: silence counts from then too
    bool killed = false;        // we asked PVM to kill it
    int frame = 0;              // from FC_PROGRESS: the frame it renders

    // Seconds of its own silence at time t: since it last spoke or was last given work (an
    // idle slave handed work is not judged by its idle time, when it had nothing to say).
    double silent_for(double t) const { return t - std::max(last_msg, last_given); }
};

struct HostInfo {
    int dtid = 0;
    std::string name;
    int cpus = 0;               // from the first FC_HELLO; 0 = unknown
    bool alive = true;
    bool grown = false;         // extra slaves for its cores already spawned
    int respawns = 0;
    int failures = 0;           // jobs that failed on it (not scene errors)
    bool excluded = false;      // left out after kHostFailures failures
};

class Cluster {
public:
    static const int kRespawns = 3;     // slaves replaced per host
    static const int kHostFailures = 3; // failed jobs after which a host is left out

    // Join or start the virtual machine and watch its hosts.
    bool start(bool force_private, const std::string &hostfile, const std::string &pvmd_name,
               double timeout, std::string &err);
    void stop() { vm_.stop(); }
    bool embedded() const { return vm_.embedded(); }
    // "private" (started for this run) or "running" (the user's) once started, else "none".
    const std::string &kind() const { return kind_; }

    int my_host() const { return my_dtid_; }

    // Wait (bounded) until the machine has `want` hosts (hosts added from the console).
    void wait_for_hosts(size_t want, double timeout);

    // Spawn `count` slaves (program slave_prog) on host; returns false if none started.
    bool spawn_on(HostInfo &host, int count);
    // One slave per core (or per_host) on every host (not the master's if !local).
    bool spawn_all(bool local, int per_host);

    // A slave said hello: learn its host's cores; the first one grows the host to one slave
    // per core. Returns the number of slaves spawned.
    int hello(SlaveInfo &s, int cpus, int per_host);

    // Hosts that joined (FC_HOSTADD): new HostInfo entries, their names reported in joined.
    void hosts_added(const std::vector<int> &dtids, std::vector<HostInfo *> &joined);

    // A job failed on the slave's host: returns true when the host is now left out.
    bool host_failed(const SlaveInfo &s);

    // POV-Ray threads for a slave: its host's cores over the slaves there that work. A slave
    // in `stalled` (its job passed its deadline: stopped, or stuck in an endless frame) is
    // given no work, so its cores go to the others of its host until it speaks again.
    int threads_for(const SlaveInfo &s, const std::set<int> &stalled) const;

    SlaveInfo *slave(int tid);
    HostInfo *host(int dtid);
    std::map<int, SlaveInfo> &slaves() { return slaves_; }
    std::map<int, HostInfo> &hosts() { return hosts_; }
    int live_slaves() const;

    std::string slave_prog;

private:
    VirtualMachine vm_;
    std::string kind_ = "none";
    int my_dtid_ = 0;
    std::map<int, SlaveInfo> slaves_;
    std::map<int, HostInfo> hosts_;     // by pvmd tid
};

} // namespace fc
