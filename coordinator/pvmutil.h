// pvmutil.h - joining or starting a PVM virtual machine, and PVM error names.
//
// fc-master uses a virtual machine that is already running for this user (PVM_TMP, default
// /tmp, holds its pvmd.<uid> file) with all its hosts. Without one it starts a private pvmd
// itself: a fresh PVM_TMP under /tmp, PVM_ALLOW_ROOT=1 when root, the pvmd as a child that
// dies with the master (PR_SET_PDEATHSIG), halted and cleaned up at the end.
#pragma once

#include <sys/types.h>

#include <string>

namespace fc {

// "PvmNoFile (No such file)" for a PVM error code.
std::string pvm_error(int code);

class VirtualMachine {
public:
    // Enrol in the user's running virtual machine, or start a private one (always when
    // force_private). hostfile (may be empty) is passed to a private pvmd, and so is name
    // (-nNAME: the master host's name, which must not resolve to a loopback address when
    // other hosts are added). Sets err and returns false on failure. On success mytid() is
    // valid.
    bool start(bool force_private, const std::string &hostfile, const std::string &name,
               double timeout, std::string &err);

    // Leave the virtual machine; a private one is halted and its PVM_TMP removed.
    void stop();

    bool embedded() const { return embedded_; }
    int mytid() const { return mytid_; }
    const std::string &tmpdir() const { return tmpdir_; }

private:
    bool start_private(const std::string &hostfile, const std::string &name, double timeout,
                       std::string &err);

    bool embedded_ = false;
    int mytid_ = -1;
    std::string tmpdir_;
    pid_t pvmd_pid_ = -1;
};

// Remove private PVM_TMP directories of earlier masters that are no longer running.
void remove_stale_private_vms();

} // namespace fc
