// check.h - the coordinator's unit tests' one assertion: CHECK(cond) reports a failed
// condition with its place and goes on; check_summary(name) ends the test's main.
#pragma once

#include <cstdio>

namespace fc {

inline int &check_failures()
{
    static int failures = 0;
    return failures;
}

// main's exit status: 0 when every CHECK held (and "NAME: all checks passed" on stdout).
inline int check_summary(const char *name)
{
    if (check_failures()) {
        fprintf(stderr, "%s: %d check(s) failed\n", name, check_failures());
        return 1;
    }
    printf("%s: all checks passed\n", name);
    return 0;
}

} // namespace fc

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            fc::check_failures()++;                                                  \
        }                                                                            \
    } while (0)
