// GroupIndex: a block record's samples by group (BlockRecord::GroupOf), with what each
// group's samples hold, so that a frame's test of the block passes over a group nothing
// of that frame concerns without reading its samples.
//
// Why. A block the changes' cones reach is tested group by group (group_fans.h), but the
// reasons a sample may be dirty without its group's cones reaching a change (a segment
// that ended on a changed unit, a tie the objects' order decided, an opaque blocker's
// test a translucent change may meet, a sample that depends on everything) were asked of
// every sample of the block: on Newton's cradle 2.8 million samples were read over 44
// frames, 1.2 million of them in groups the cones reach. The index answers those
// questions per group; a group's flags and unit mask are a superset of its samples', so
// a group it passes over holds no sample that could be dirty.
#ifndef POVRAYFC_GROUP_INDEX_H
#define POVRAYFC_GROUP_INDEX_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

struct GroupIndex {
    // flags: what one of the group's samples holds.
    static constexpr std::uint8_t kEverything = 1;       // StoredSample::kEverything segments
    static constexpr std::uint8_t kOrderSensitive = 2;   // StoredSample::orderSensitive
    static constexpr std::uint8_t kOpaqueBlockerTest = 4;  // a segment with Segment::kOpaqueBlocker
    static constexpr std::uint8_t kStaleShadowTests = 8;   // StoredSample::shadowStale

    std::vector<std::uint32_t> start;     // per group, its first entry of `samples`; and the end
    std::vector<std::uint32_t> samples;   // indices into BlockRecord::samples, group by group
    std::vector<std::uint64_t> unitMask;  // per group: UnitMaskBit of every unit its segments ended on
    std::vector<std::uint8_t> flags;      // per group

    std::uint32_t Begin(std::size_t group) const { return start[group]; }
    std::uint32_t End(std::size_t group) const { return start[group + 1]; }
    void Clear() {
        start.clear();
        samples.clear();
        unitMask.clear();
        flags.clear();
    }
    std::size_t MemoryBytes() const {
        return (start.capacity() + samples.capacity()) * sizeof(std::uint32_t) +
               unitMask.capacity() * sizeof(std::uint64_t) + flags.capacity();
    }
};

}  // namespace povrayfc

#endif
