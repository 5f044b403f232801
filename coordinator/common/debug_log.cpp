// debug_log.cpp - the FC_DEBUG_LOG trace (see debug_log.h).
#include "debug_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "clock.h"
#include "files.h"
#include "text.h"

namespace fc {

void debug_log(const char *format, ...)
{
    static int fd = -2;
    if (fd == -2) {
        const char *path = getenv("FC_DEBUG_LOG");
        fd = (path && *path) ? open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
    }
    if (fd < 0)
        return;
    va_list ap;
    va_start(ap, format);
    char msg[1024];
    vsnprintf(msg, sizeof msg, format, ap);
    va_end(ap);
    static std::string prog;
    if (prog.empty()) {
        char buf[256] = {0};
        ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
        prog = n > 0 ? base_name(std::string(buf, size_t(n))) : "fc";
    }
    std::string line = strf("%.3f %s[%d] %s\n", now(), prog.c_str(), int(getpid()), msg);
    ssize_t w = write(fd, line.data(), line.size());
    (void)w;
}

} // namespace fc
