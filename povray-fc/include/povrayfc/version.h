// povray-fc version, shown by the patched POV-Ray in --version and its banner.
#ifndef POVRAYFC_VERSION_H
#define POVRAYFC_VERSION_H

#define POVRAYFC_VERSION "0.1.0"

#ifdef __cplusplus
namespace povrayfc {
// The version string compiled into the library; the patched binary prints this one,
// so a binary linked against a stale library shows it.
const char *LibraryVersion();
}
#endif

#endif
