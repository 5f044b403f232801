// durable_write.cpp - files on disk whole or not at all (see durable_write.h).
#include "durable_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "files.h"
#include "text.h"

namespace fc {

bool write_file_durably(const std::string &path, const void *data, size_t size, std::string &err)
{
    int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        return sys_fail(err, "open " + path);
    const char *p = static_cast<const char *>(data);
    size_t left = size;
    bool ok = true;
    std::string call;
    while (left > 0) {
        ssize_t n = write(fd, p, left);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (n == 0)
                errno = ENOSPC;     // a write that makes no progress: nothing fits any more
            ok = false;
            call = "write " + path;
            break;
        }
        p += n;
        left -= size_t(n);
    }
    // A full disk may only show at fsync (delayed allocation) or close (network file systems).
    if (ok && fsync(fd) != 0) {
        ok = false;
        call = "fsync " + path;
    }
    struct stat st;
    if (ok && fstat(fd, &st) != 0) {
        ok = false;
        call = "fstat " + path;
    }
    if (ok && st.st_size != off_t(size)) {
        errno = EIO;
        err = strf("%s has %lld bytes on disk, %zu were written", path.c_str(),
                   (long long)st.st_size, size);
        close(fd);
        unlink(path.c_str());
        return false;
    }
    int saved = errno;
    if (close(fd) != 0 && ok) {
        ok = false;
        call = "close " + path;
        saved = errno;
    }
    if (!ok) {
        errno = saved;
        sys_fail(err, call);
        unlink(path.c_str());
        errno = saved;
        return false;
    }
    return true;
}

bool sync_dir(const std::string &dir, std::string &err)
{
    int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return sys_fail(err, "open " + dir);
    // Some file systems cannot sync a directory (EINVAL): the rename is as durable as they get.
    bool ok = fsync(fd) == 0 || errno == EINVAL;
    int saved = errno;
    close(fd);
    errno = saved;
    return ok || sys_fail(err, "fsync " + dir);
}

} // namespace fc
