// temp_dirs.cpp - private working directories (see temp_dirs.h).
#include "temp_dirs.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "files.h"
#include "text.h"

namespace fc {

std::string temp_root()
{
    const char *t = getenv("TMPDIR");
    struct stat st;
    if (t && *t && stat(t, &st) == 0 && S_ISDIR(st.st_mode))
        return t;
    return "/tmp";
}

bool make_temp_dir(const std::string &parent, const std::string &prefix, std::string &dir,
                   std::string &err)
{
    std::string templ = parent + "/" + prefix + "XXXXXX";
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data()))
        return sys_fail(err, "mkdtemp " + templ);
    dir = buf.data();
    return true;
}

void remove_tree(const std::string &path)
{
    struct stat st;
    if (lstat(path.c_str(), &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        if (DIR *d = opendir(path.c_str())) {
            while (struct dirent *e = readdir(d)) {
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                    continue;
                remove_tree(path + "/" + e->d_name);
            }
            closedir(d);
        }
        rmdir(path.c_str());
    } else {
        unlink(path.c_str());
    }
}

void remove_stale_dirs(const std::string &parent, const std::string &prefix)
{
    DIR *d = opendir(parent.c_str());
    if (!d)
        return;
    while (struct dirent *e = readdir(d)) {
        std::string name = e->d_name;
        if (!starts_with(name, prefix))
            continue;
        int pid = atoi(name.c_str() + prefix.size());
        if (pid <= 0 || name.find('-', prefix.size()) == std::string::npos)
            continue;
        std::string path = parent + "/" + name;
        struct stat st;
        if (lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != getuid())
            continue;
        if (kill(pid, 0) == 0 || errno == EPERM)
            continue;   // still running
        remove_tree(path);
    }
    closedir(d);
}

} // namespace fc
