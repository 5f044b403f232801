// Tied searches kept with a sample and run again (tie_replay.h).
#include "povrayfc/tie_replay.h"

#include <cstring>

#include "povrayfc/ray_recording.h"
#include "povrayfc/segment.h"
#include "byte_io.h"

namespace povrayfc {

void PackTiedSearches(const std::vector<TiedSearch> &searches, bool complete, std::vector<std::uint8_t> &packed) {
    if (!complete || searches.size() > kMaxTiedSearches) {
        packed.push_back(kTiesUnknown);
        return;
    }
    const std::size_t at = packed.size();
    packed.resize(at + 1 + searches.size() * kTiedSearchBytes);
    std::uint8_t *out = packed.data() + at;
    *out++ = std::uint8_t(searches.size());
    for (const TiedSearch &s : searches) {
        Put(out, s.kind);
        Put(out, s.rayFlags);
        for (double v : s.origin) Put(out, v);
        for (double v : s.direction) Put(out, v);
        Put(out, s.start);
        Put(out, s.depth);
        Put(out, s.unit);
        Put(out, s.objectHash);
    }
}

std::size_t TiedSearchesBytes(const std::uint8_t *bytes) {
    return bytes[0] == kTiesUnknown ? 1 : 1 + std::size_t(bytes[0]) * kTiedSearchBytes;
}

bool UnpackTiedSearches(const std::uint8_t *bytes, std::vector<TiedSearch> &searches) {
    searches.clear();
    if (bytes[0] == kTiesUnknown) return false;
    const std::uint8_t *in = bytes + 1;
    searches.resize(bytes[0]);
    for (TiedSearch &s : searches) {
        Get(in, s.kind);
        Get(in, s.rayFlags);
        for (double &v : s.origin) Get(in, v);
        for (double &v : s.direction) Get(in, v);
        Get(in, s.start);
        Get(in, s.depth);
        Get(in, s.unit);
        Get(in, s.objectHash);
    }
    return true;
}

bool TiedSearchesHold(const std::uint8_t *bytes, TieReplayer *replayer, const std::uint32_t *unitIds,
                      std::size_t unitCount) {
    if (!replayer) return false;
    // Scratch per thread: a block tests its samples one after another.
    thread_local std::vector<TiedSearch> searches;
    if (!UnpackTiedSearches(bytes, searches)) return false;
    for (const TiedSearch &s : searches) {
        double depth;
        std::uint32_t unitIndex, id;
        std::uint64_t hash;
        if (!replayer->Replay(s, depth, unitIndex, hash)) return false;
        // An object without a unit fc knows cannot be the one found before.
        if (!SegmentUnitOf(unitIndex, unitIds, unitCount, id)) return false;
        // Exactly the same depth (bit for bit), object and part.
        if (std::memcmp(&depth, &s.depth, sizeof depth) != 0 || id != s.unit || hash != s.objectHash) return false;
    }
    return true;
}

}  // namespace povrayfc
