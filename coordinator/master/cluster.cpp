// cluster.cpp - the virtual machine, its hosts and the slaves on them (see cluster.h).
#include "cluster.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include <pvm3.h>

#include "clock.h"
#include "host_info.h"
#include "protocol.h"
#include "pvm_error.h"
#include "text.h"
#include "watchdog.h"

namespace fc {

bool Cluster::start(bool force_private, const std::string &hostfile, const std::string &pvmd_name,
                    double timeout, std::string &err)
{
    if (!vm_.start(force_private, hostfile, pvmd_name, timeout, err))
        return false;
    kind_ = vm_.embedded() ? "private" : "running";
    watchdog::Guard guard("pvm_config and pvm_notify", watchdog::kLocalPvmBound);
    my_dtid_ = pvm_tidtohost(vm_.mytid());
    int nhost = 0, narch = 0;
    struct pvmhostinfo *hi = nullptr;
    int r = pvm_config(&nhost, &narch, &hi);
    if (r < 0) {
        err = "pvm_config: " + pvm_error(r);
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

void Cluster::wait_for_hosts(size_t want, double timeout)
{
    double deadline = now() + timeout;
    for (;;) {
        watchdog::Guard guard("pvm_config", watchdog::kLocalPvmBound);
        int nhost = 0, narch = 0;
        struct pvmhostinfo *hi = nullptr;
        if (pvm_config(&nhost, &narch, &hi) < 0)
            return;
        for (int i = 0; i < nhost; i++) {
            if (hi[i].hi_tid == my_dtid_ || hosts_.count(hi[i].hi_tid))
                continue;
            HostInfo h;
            h.dtid = hi[i].hi_tid;
            h.name = hi[i].hi_name;
            hosts_[h.dtid] = h;
            pvm_notify(PvmHostDelete, FC_HOSTDEL, 1, &h.dtid);
        }
        if (hosts_.size() >= want || now() >= deadline || watchdog::stop_requested())
            return;
        usleep(100000);
    }
}

bool Cluster::spawn_on(HostInfo &host, int count)
{
    if (count <= 0 || host.excluded || !host.alive)
        return false;
    std::vector<int> tids(size_t(count), 0);
    char *args[] = {nullptr};
    int n = 0;
    {
        // A spawn waits for the host's pvmd: one that died blocks it until PVM declares the
        // host dead, minutes later.
        watchdog::Guard guard("pvm_spawn on host " + host.name, 60,
                              "host " + host.name + " does not answer; remove it from the virtual "
                              "machine ('delete " + host.name + "' in the pvm console) and run "
                              "the same command again");
        n = pvm_spawn(const_cast<char *>(slave_prog.c_str()), args, PvmTaskHost,
                      const_cast<char *>(host.name.c_str()), count, tids.data());
    }
    std::vector<int> ok;
    for (int i = 0; i < count; i++) {
        if (i < std::max(n, 0) && tids[size_t(i)] > 0) {
            ok.push_back(tids[size_t(i)]);
        } else {
            int code = n < 0 ? n : tids[size_t(i)];
            fprintf(stderr, "fc-master: cannot start %s on host %s: %s\n", slave_prog.c_str(),
                    host.name.c_str(), pvm_error(code).c_str());
            if (code == PvmNoFile)
                fprintf(stderr, "fc-master: the slave program must exist at the same absolute "
                                "path on every host\n");
            break;
        }
    }
    if (ok.empty())
        return false;
    watchdog::Guard guard("pvm_notify", watchdog::kLocalPvmBound);
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
    }
    return int(ok.size()) == count;
}

bool Cluster::spawn_all(bool local, int per_host)
{
    bool any = false;
    for (auto &kv : hosts_) {
        HostInfo &h = kv.second;
        if (!local && h.dtid == my_dtid_)
            continue;
        int n = per_host > 0 ? per_host : (h.cpus > 0 ? h.cpus : 1);
        if (per_host > 0 || h.cpus > 0)
            h.grown = true;
        spawn_on(h, n);
        any = any || std::any_of(slaves_.begin(), slaves_.end(),
                                 [&](auto &s) { return s.second.dtid == h.dtid; });
    }
    return any;
}

int Cluster::hello(SlaveInfo &s, int cpus, int per_host)
{
    HostInfo &host = hosts_[s.dtid];
    if (host.cpus == 0)
        host.cpus = std::max(1, cpus);
    if (host.grown || !host.alive || host.excluded)
        return 0;
    host.grown = true;
    int more = (per_host > 0 ? per_host : host.cpus) - 1;
    if (more > 0)
        spawn_on(host, more);
    return more;
}

void Cluster::hosts_added(const std::vector<int> &added, std::vector<HostInfo *> &joined)
{
    watchdog::Guard guard("pvm_config", watchdog::kLocalPvmBound);
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
            joined.push_back(&hosts_[dtid]);
        }
    }
}

bool Cluster::host_failed(const SlaveInfo &s)
{
    auto h = hosts_.find(s.dtid);
    if (h == hosts_.end() || h->second.excluded)
        return false;
    if (++h->second.failures < kHostFailures)
        return false;
    h->second.excluded = true;
    return true;
}

int Cluster::threads_for(const SlaveInfo &s, const std::set<int> &stalled) const
{
    auto h = hosts_.find(s.dtid);
    int cpus = h == hosts_.end() ? 1 : std::max(1, h->second.cpus);
    int n = 0;
    for (auto &kv : slaves_)
        if (kv.second.dtid == s.dtid && kv.second.state != SlaveState::Gone &&
            (kv.first == s.tid || !stalled.count(kv.first)))
            n++;
    return std::max(1, cpus / std::max(1, n));
}

SlaveInfo *Cluster::slave(int tid)
{
    auto it = slaves_.find(tid);
    return it == slaves_.end() ? nullptr : &it->second;
}

HostInfo *Cluster::host(int dtid)
{
    auto it = hosts_.find(dtid);
    return it == hosts_.end() ? nullptr : &it->second;
}

int Cluster::live_slaves() const
{
    int n = 0;
    for (auto &kv : slaves_)
        n += kv.second.state != SlaveState::Gone;
    return n;
}

} // namespace fc
