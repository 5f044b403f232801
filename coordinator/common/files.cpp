// files.cpp - paths and plain files (see files.h).
#include "files.h"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace fc {

bool sys_fail(std::string &err, const std::string &call)
{
    err = call + ": " + strerror(errno);
    return false;
}

std::string absolute_path(const std::string &path)
{
    char buf[PATH_MAX];
    if (realpath(path.c_str(), buf))
        return buf;
    if (!path.empty() && path[0] == '/')
        return path;
    char cwd[PATH_MAX];
    if (!getcwd(cwd, sizeof cwd))
        return path;
    return std::string(cwd) + "/" + path;
}

std::string dir_name(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos)
        return ".";
    if (slash == 0)
        return "/";
    return path.substr(0, slash);
}

std::string base_name(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool file_exists(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

bool is_executable(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
}

std::string which(const std::string &name)
{
    if (name.find('/') != std::string::npos)
        return is_executable(name) ? name : std::string();
    const char *path = getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        size_t end = dirs.find(':', start);
        if (end == std::string::npos)
            end = dirs.size();
        std::string dir = dirs.substr(start, end - start);
        if (!dir.empty()) {
            std::string cand = dir + "/" + name;
            if (is_executable(cand))
                return cand;
        }
        start = end + 1;
    }
    return std::string();
}

bool make_dirs(const std::string &dir, std::string &err)
{
    std::string acc;
    size_t pos = 0;
    while (pos <= dir.size()) {
        size_t slash = dir.find('/', pos);
        if (slash == std::string::npos)
            slash = dir.size();
        acc = dir.substr(0, slash);
        if (!acc.empty() && mkdir(acc.c_str(), 0777) != 0 && errno != EEXIST)
            return sys_fail(err, "mkdir " + acc);
        pos = slash + 1;
    }
    struct stat st;
    if (stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        err = dir + " is not a directory";
        return false;
    }
    return true;
}

bool write_text(const std::string &path, const std::string &text, std::string &err)
{
    FILE *f = fopen(path.c_str(), "w");
    if (!f)
        return sys_fail(err, "fopen " + path);
    bool ok = fwrite(text.data(), 1, text.size(), f) == text.size();
    if (fclose(f) != 0)
        ok = false;
    if (!ok)
        return sys_fail(err, "write " + path);
    return true;
}

bool read_text(const std::string &path, std::string &text, std::string &err)
{
    FILE *f = fopen(path.c_str(), "r");
    if (!f)
        return sys_fail(err, "fopen " + path);
    text.clear();
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        text.append(buf, n);
    bool bad = ferror(f) != 0;
    fclose(f);
    if (bad)
        return sys_fail(err, "read " + path);
    return true;
}

bool free_bytes(const std::string &path, unsigned long long &bytes, std::string &err)
{
    struct statvfs sv;
    if (statvfs(path.c_str(), &sv) != 0)
        return sys_fail(err, "statvfs " + path);
    bytes = (unsigned long long)sv.f_bavail * (unsigned long long)sv.f_frsize;
    return true;
}

} // namespace fc
