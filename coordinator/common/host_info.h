// host_info.h - what a process knows of the machine it runs on and of itself: the host's name
// and processors, and the directory of its own executable (where its helpers live).
#pragma once

#include <string>

namespace fc {

// This machine's host name (gethostname), and its number of online CPUs (>= 1).
std::string host_name();
int cpu_count();

// Absolute path of the running executable's directory (from /proc/self/exe).
std::string self_dir();

} // namespace fc
