// files.h - paths and plain files: names, existence, the search path, whole-file reads and
// writes, free space.
//
// One error convention in fc-master and fc-slave: a function that can fail returns bool
// (true = OK) and fills a caller-owned std::string with a message that names the failing call
// and, for system calls, strerror(errno) (sys_fail).
#pragma once

#include <string>

namespace fc {

// Fill err with "<call>: <strerror(errno)>" and return false.
bool sys_fail(std::string &err, const std::string &call);

// path made absolute: resolved (realpath) when it exists, else joined to the working directory.
std::string absolute_path(const std::string &path);

// Directory that holds path ("." when none), and the last component of path.
std::string dir_name(const std::string &path);
std::string base_name(const std::string &path);

bool file_exists(const std::string &path);
bool is_executable(const std::string &path);

// Search PATH for an executable; returns "" when not found. Names with a slash are checked as is.
std::string which(const std::string &name);

// Create dir and its missing parents; false with err (strerror) unless dir is a directory.
bool make_dirs(const std::string &dir, std::string &err);

// Write text to path (truncating), or read a whole file into text; false with err.
bool write_text(const std::string &path, const std::string &text, std::string &err);
bool read_text(const std::string &path, std::string &text, std::string &err);

// Bytes available to us on the file system holding path; false with err.
bool free_bytes(const std::string &path, unsigned long long &bytes, std::string &err);

} // namespace fc
