// Text forms of Vec3 and Box for error messages and "everything dirty" reasons.
#include "povrayfc/geometry.h"

#include <cstdio>

namespace povrayfc {

std::string ToString(const Vec3 &v) {
    // %.17g round-trips a double, so a reported bound can be pasted back into a test.
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", v.x, v.y, v.z);
    return buf;
}

std::string ToString(const Box &b) { return "[" + ToString(b.lo) + ", " + ToString(b.hi) + "]"; }

}  // namespace povrayfc
