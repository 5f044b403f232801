// temp_dirs.h - private working directories of fc-master and fc-slave, and cleaning up those a
// killed process left behind.
#pragma once

#include <string>

namespace fc {

// Where private directories go: $TMPDIR when it names a directory, else /tmp.
std::string temp_root();

// Create a fresh private directory "<parent>/<prefix>XXXXXX"; on success dir holds its path.
bool make_temp_dir(const std::string &parent, const std::string &prefix, std::string &dir,
                   std::string &err);

// Remove a directory tree (no symlinks followed). Errors are ignored: used for cleanup.
void remove_tree(const std::string &path);

// Remove directories "<parent>/<prefix><pid>-*" owned by us whose process <pid> is gone
// (left behind by a killed fc-master or fc-slave).
void remove_stale_dirs(const std::string &parent, const std::string &prefix);

} // namespace fc
