// The library's version string.
#include "povrayfc/version.h"

namespace povrayfc {
const char *LibraryVersion() { return POVRAYFC_VERSION; }
}
