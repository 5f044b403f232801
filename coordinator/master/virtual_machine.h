// virtual_machine.h - the PVM virtual machine fc-master renders on: joined or started.
//
// fc-master uses a virtual machine that is already running for this user (PVM_TMP, default
// /tmp, holds its pvmd.<uid> file) with all its hosts. Without one it starts a private pvmd
// itself: a fresh PVM_TMP under /tmp, PVM_ALLOW_ROOT=1 when root, the pvmd as a child that
// dies with the master (PR_SET_PDEATHSIG), halted and cleaned up at the end.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace fc {

class VirtualMachine {
public:
    // Enrol in the user's running virtual machine, or start a private one (always when
    // force_private), then add the hosts of hostfile (may be empty; a private pvmd also gets
    // its per-host options). name (-nNAME) is the master host's name for a private pvmd,
    // which must not resolve to a loopback address when other hosts are added. Sets err and
    // returns false on failure, naming every host that could not be added and why. On
    // success mytid() is valid.
    bool start(bool force_private, const std::string &hostfile, const std::string &name,
               double timeout, std::string &err);

    // Leave the virtual machine; a private one is halted and its PVM_TMP removed.
    void stop();

    bool embedded() const { return embedded_; }
    int mytid() const { return mytid_; }
    const std::string &tmpdir() const { return tmpdir_; }

private:
    bool add_hosts(const std::string &hostfile, std::string &err);
    bool start_private(const std::string &hostfile, const std::string &name, double timeout,
                       std::string &err);

    double add_timeout_ = 60;       // the start's timeout: adding hosts may take that long
    bool embedded_ = false;
    int mytid_ = -1;
    std::string tmpdir_;
    pid_t pvmd_pid_ = -1;
};

// The hosts a pvmd host file names (lines that are not comments, defaults or '&' entries).
std::vector<std::string> hostfile_hosts(const std::string &hostfile);

// Remove private PVM_TMP directories of earlier masters that are no longer running.
void remove_stale_private_vms();

} // namespace fc
