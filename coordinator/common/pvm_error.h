// pvm_error.h - PVM's error codes in words, for every message that reports a PVM call.
#pragma once

#include <string>

namespace fc {

// "PvmNoFile (no such file)" for a PVM error code; "PVM error N" for an unknown one.
std::string pvm_error(int code);

} // namespace fc
