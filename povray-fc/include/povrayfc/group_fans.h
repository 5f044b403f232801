// GroupFans: a block's cones per group of its samples (BlockRecord::GroupOf), so that a
// change that the block's cones reach is tested only against the segments of the groups
// whose own cones reach it too.
//
// Why. A block's shadow cone holds the shadow tests of every surface its pixels see,
// reflections' hit points included, and on a scene with mirrors (Newton's chrome marbles
// reflect the whole room) it spans half the scene: a moving object reached 8 of 10 blocks
// that way, and every segment of those blocks was tested. Seen from a group of 8x8
// pixels the cones are narrow again: on Newton the groups a change reaches hold 43% of
// the samples of the blocks it reaches. The block's own cones are merged from its
// groups' (MergeFans), so the segments are swept once.
#ifndef POVRAYFC_GROUP_FANS_H
#define POVRAYFC_GROUP_FANS_H

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "povrayfc/sample_store.h"

namespace povrayfc {

// Builds `record.groupFans`, `record.fans` and `record.groupIndex` from its samples' segments.
void BuildRecordFans(BlockRecord &record);

// The same for a replayed block, cheaply: `record.groupFans` hold its groups' cones from
// before; `segments` and `fanOf` the segments of the samples traced anew, as unpacking
// gives them (the recorder's), `added` each such sample's (first, count) in them and
// `addedGroup` its group. The samples kept from before keep their segments inside the old
// cones; only the groups that gained segments grow (a replayed block traces a few of its
// samples) and only the added segments' fan numbers are validated. The group index is
// left as it was: the caller builds it anew (BuildGroupIndex) or adds the samples traced
// in place (AddToGroupIndex).
void GrowRecordFans(BlockRecord &record, const Segment *segments, std::uint8_t *fanOf,
                    const std::vector<std::pair<std::size_t, std::size_t>> &added,
                    const std::vector<std::uint32_t> &addedGroup);

// Builds `record.groupIndex` from its samples and their packed units. With `before`: the
// samples `kept` marks were taken over from a record of the same block whose index that
// is, and what their groups held there is carried over (a superset, as AddToGroupIndex
// keeps) instead of reading their units again; only the others' are read.
void BuildGroupIndex(BlockRecord &record, const GroupIndex *before = nullptr,
                     const std::vector<std::uint8_t> *kept = nullptr);
// Adds what sample `s` of `record` holds to its group's flags and unit mask, which stay a
// superset of their samples' (a sample traced again in place: bits are never taken out).
void AddToGroupIndex(BlockRecord &record, const StoredSample &s);

}  // namespace povrayfc

#endif
