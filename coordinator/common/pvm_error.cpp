// pvm_error.cpp - PVM's error codes in words (see pvm_error.h).
#include "pvm_error.h"

#include <pvm3.h>

#include "text.h"

namespace fc {

std::string pvm_error(int code)
{
    static const struct { int code; const char *name, *text; } table[] = {
        {PvmBadParam, "PvmBadParam", "bad parameter"},
        {PvmMismatch, "PvmMismatch", "parameter mismatch"},
        {PvmOverflow, "PvmOverflow", "value too large"},
        {PvmNoData, "PvmNoData", "end of buffer"},
        {PvmNoHost, "PvmNoHost", "no such host"},
        {PvmNoFile, "PvmNoFile", "no such file"},
        {PvmDenied, "PvmDenied", "permission denied"},
        {PvmNoMem, "PvmNoMem", "malloc failed"},
        {PvmBadMsg, "PvmBadMsg", "can't decode message"},
        {PvmSysErr, "PvmSysErr", "can't contact local daemon"},
        {PvmNoBuf, "PvmNoBuf", "no current buffer"},
        {PvmNoSuchBuf, "PvmNoSuchBuf", "no such buffer"},
        {PvmHostFail, "PvmHostFail", "host failed"},
        {PvmNoParent, "PvmNoParent", "no parent task"},
        {PvmNotImpl, "PvmNotImpl", "not implemented"},
        {PvmDSysErr, "PvmDSysErr", "pvmd system error"},
        {PvmBadVersion, "PvmBadVersion", "version mismatch"},
        {PvmOutOfRes, "PvmOutOfRes", "out of resources"},
        {PvmDupHost, "PvmDupHost", "duplicate host"},
        {PvmCantStart, "PvmCantStart", "can't start pvmd"},
        {PvmAlready, "PvmAlready", "already in progress"},
        {PvmNoTask, "PvmNoTask", "no such task"},
        {PvmNotFound, "PvmNotFound", "not found"},
        {PvmExists, "PvmExists", "already exists"},
        {PvmHostrNMstr, "PvmHostrNMstr", "hoster run on non-master host"},
        {PvmParentNotSet, "PvmParentNotSet", "spawning parent set PvmNoSpawnParent"},
        {PvmIPLoopback, "PvmIPLoopback", "master host's IP is loopback"},
    };
    for (auto &e : table)
        if (e.code == code)
            return strf("%s (%s)", e.name, e.text);
    return strf("PVM error %d", code);
}

} // namespace fc
