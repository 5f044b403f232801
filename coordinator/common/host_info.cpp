// host_info.cpp - the host and the running executable (see host_info.h).
#include "host_info.h"

#include <limits.h>
#include <unistd.h>

#include "files.h"

namespace fc {

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

} // namespace fc
