// clock.h - the one clock of fc-master and fc-slave: seconds on CLOCK_MONOTONIC, which no
// change of the wall clock moves (timeouts, deadlines, rates).
#pragma once

namespace fc {

// Seconds since an arbitrary fixed point (CLOCK_MONOTONIC).
double now();

} // namespace fc
