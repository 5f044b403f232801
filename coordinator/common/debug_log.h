// debug_log.h - the protocol trace of a run, for diagnosing it: set FC_DEBUG_LOG=/path and the
// master and every slave of a machine append one line per event there
// (scripts/frame-timeline turns it into a table).
#pragma once

namespace fc {

// Append one line, "<seconds> <program>[<pid>] <message>", to $FC_DEBUG_LOG (if set).
void debug_log(const char *format, ...) __attribute__((format(printf, 1, 2)));

} // namespace fc
