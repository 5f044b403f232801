// Plain values written to and read from a byte stream, unaligned, in the machine's order:
// the records a frame keeps are read back by the same binary in the same run.
#ifndef POVRAYFC_BYTE_IO_H
#define POVRAYFC_BYTE_IO_H

#include <cstdint>
#include <cstring>

namespace povrayfc {

template <class T>
void Put(std::uint8_t *&out, const T &value) {
    std::memcpy(out, &value, sizeof value);
    out += sizeof value;
}

template <class T>
void Get(const std::uint8_t *&in, T &value) {
    std::memcpy(&value, in, sizeof value);
    in += sizeof value;
}

}  // namespace povrayfc

#endif
