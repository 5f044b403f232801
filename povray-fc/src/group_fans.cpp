// GroupFans: per-group cones of a block's samples, built and grown, and the block's
// cones merged from them.
#include "povrayfc/group_fans.h"

namespace povrayfc {

void BuildRecordFans(BlockRecord &record) {
    // The record's segments, unpacked, numbered in its samples' order.
    thread_local UnpackScratch scratch;
    thread_local std::vector<std::vector<std::uint32_t>> members;
    std::size_t total = 0;
    for (const StoredSample &s : record.samples)
        if (s.segmentCount != StoredSample::kEverything) total += s.segmentCount;
    scratch.Fit(total);
    members.resize(record.GroupCount());
    for (std::vector<std::uint32_t> &m : members) m.clear();
    std::uint32_t first = 0;
    for (StoredSample &s : record.samples) {
        if (s.segmentCount == StoredSample::kEverything) continue;
        if (!record.UnpackOrForget(s, scratch.segments.data() + first, scratch.fans.data() + first)) continue;
        std::vector<std::uint32_t> &m = members[s.group];
        for (std::uint32_t k = 0; k < s.segmentCount; ++k) m.push_back(first + k);
        first += s.segmentCount;
    }
    record.groupFans.clear();
    record.groupFans.reserve(record.GroupCount());
    for (std::size_t g = 0; g < record.GroupCount(); ++g)
        record.groupFans.push_back(BuildFansOf(scratch.segments.data(), scratch.fans.data(), record.apexes, members[g]));
    record.fans = MergeFans(record.groupFans, record.apexes);
    BuildGroupIndex(record);
    record.fansBuilt = true;
    record.grownSegments = 0;
}

void GrowRecordFans(BlockRecord &record, const Segment *segments, std::uint8_t *fanOf,
                    const std::vector<std::pair<std::size_t, std::size_t>> &added,
                    const std::vector<std::uint32_t> &addedGroup) {
    thread_local std::vector<std::vector<std::pair<std::size_t, std::size_t>>> addedTo;
    addedTo.resize(record.groupFans.size());
    for (auto &a : addedTo) a.clear();
    for (std::size_t i = 0; i < added.size(); ++i) {
        addedTo[addedGroup[i]].push_back(added[i]);
        for (std::size_t k = added[i].first; k < added[i].first + added[i].second; ++k)
            if (fanOf[k] >= record.apexes.count) fanOf[k] = BlockFans::kLoose;
    }
    for (std::size_t g = 0; g < record.groupFans.size(); ++g)
        if (!addedTo[g].empty())
            record.groupFans[g] = GrowFans(record.groupFans[g], segments, fanOf, record.apexes, addedTo[g]);
    record.fans = MergeFans(record.groupFans, record.apexes);
    record.fansBuilt = true;
}

void BuildGroupIndex(BlockRecord &record) {
    GroupIndex &index = record.groupIndex;
    const std::size_t groups = record.GroupCount();
    index.start.assign(groups + 1, 0);
    index.unitMask.assign(groups, 0);
    index.flags.assign(groups, 0);
    for (const StoredSample &s : record.samples) {
        ++index.start[s.group + 1];
        AddToGroupIndex(record, s);
    }
    for (std::size_t g = 0; g < groups; ++g) index.start[g + 1] += index.start[g];
    index.samples.resize(record.samples.size());
    thread_local std::vector<std::uint32_t> next;
    next.assign(index.start.begin(), index.start.end() - 1);
    for (std::uint32_t i = 0; i < record.samples.size(); ++i) index.samples[next[record.samples[i].group]++] = i;
}

void AddToGroupIndex(BlockRecord &record, const StoredSample &s) {
    std::uint8_t &flags = record.groupIndex.flags[s.group];
    if (s.orderSensitive) flags |= GroupIndex::kOrderSensitive;
    if (s.segmentCount == StoredSample::kEverything) {
        flags |= GroupIndex::kEverything;
        return;
    }
    std::uint64_t &mask = record.groupIndex.unitMask[s.group];
    const std::uint8_t *p = record.packed.data() + s.firstByte;
    for (std::uint32_t k = 0; k < s.segmentCount; ++k) {
        std::uint32_t unit;
        p = NextPacked(p, unit);
        if (unit == Segment::kNoUnit) continue;
        mask |= UnitMaskBit(unit & ~Segment::kOpaqueBlocker);
        if (unit & Segment::kOpaqueBlocker) flags |= GroupIndex::kOpaqueBlockerTest;
    }
}

}  // namespace povrayfc
