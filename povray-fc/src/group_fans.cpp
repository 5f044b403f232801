// GroupFans: per-group cones of a block's samples, built and grown, and the block's
// cones merged from them.
#include "povrayfc/group_fans.h"

namespace povrayfc {

namespace {

// The flags a sample gives its group by itself (kEverything, kOrderSensitive,
// kStaleShadowTests).
void AddSampleFlags(GroupIndex &index, const StoredSample &s) {
    std::uint8_t &flags = index.flags[s.group];
    if (s.orderSensitive) flags |= GroupIndex::kOrderSensitive;
    if (s.segmentCount == StoredSample::kEverything) flags |= GroupIndex::kEverything;
    if (s.shadowStale) flags |= GroupIndex::kStaleShadowTests;
}

// What a segment that ended on `unit` (a Segment::unit value) gives its sample's group.
void AddUnit(GroupIndex &index, std::uint32_t group, std::uint32_t unit) {
    if (unit == Segment::kNoUnit) return;
    index.unitMask[group] |= UnitMaskBit(unit & ~Segment::kOpaqueBlocker);
    if (unit & Segment::kOpaqueBlocker) index.flags[group] |= GroupIndex::kOpaqueBlockerTest;
}

// The unit mask and opaque-blocker flag its packed segments give it.
void AddSampleUnits(BlockRecord &record, const StoredSample &s) {
    if (s.segmentCount == StoredSample::kEverything) return;
    const std::uint8_t *p = record.packed.data() + s.firstByte;
    for (std::uint32_t k = 0; k < s.segmentCount; ++k) {
        std::uint32_t unit;
        p = NextPacked(p, unit);
        AddUnit(record.groupIndex, s.group, unit);
    }
}

// Indexes the record's samples by group, with the flags they give by themselves; every
// unit mask 0.
void IndexSamplesByGroup(BlockRecord &record) {
    GroupIndex &index = record.groupIndex;
    const std::size_t groups = record.GroupCount();
    index.start.assign(groups + 1, 0);
    index.unitMask.assign(groups, 0);
    index.flags.assign(groups, 0);
    for (const StoredSample &s : record.samples) {
        ++index.start[s.group + 1];
        AddSampleFlags(index, s);
    }
    for (std::size_t g = 0; g < groups; ++g) index.start[g + 1] += index.start[g];
    index.samples.resize(record.samples.size());
    thread_local std::vector<std::uint32_t> next;
    next.assign(index.start.begin(), index.start.end() - 1);
    for (std::uint32_t i = 0; i < record.samples.size(); ++i) index.samples[next[record.samples[i].group]++] = i;
}

}  // namespace

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
    // The group index takes each group's units from the segments as they are unpacked.
    IndexSamplesByGroup(record);
    GroupIndex &index = record.groupIndex;
    std::uint32_t first = 0;
    for (StoredSample &s : record.samples) {
        if (s.segmentCount == StoredSample::kEverything) continue;
        Segment *segments = scratch.segments.data() + first;
        if (!record.UnpackOrForget(s, segments, scratch.fans.data() + first)) {
            AddSampleFlags(index, s);  // it depends on everything now
            continue;
        }
        std::vector<std::uint32_t> &m = members[s.group];
        for (std::uint32_t k = 0; k < s.segmentCount; ++k) {
            m.push_back(first + k);
            AddUnit(index, s.group, segments[k].unit);
        }
        first += s.segmentCount;
    }
    record.groupFans.clear();
    record.groupFans.reserve(record.GroupCount());
    for (std::size_t g = 0; g < record.GroupCount(); ++g)
        record.groupFans.push_back(BuildFansOf(scratch.segments.data(), scratch.fans.data(), record.apexes, members[g]));
    record.fans = MergeFans(record.groupFans, record.apexes);
    record.unitMask = 0;  // exact again, where updates only ever added bits
    for (std::uint64_t mask : index.unitMask) record.unitMask |= mask;
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

void BuildGroupIndex(BlockRecord &record, const GroupIndex *before, const std::vector<std::uint8_t> *kept) {
    IndexSamplesByGroup(record);
    GroupIndex &index = record.groupIndex;
    if (before) {
        for (std::size_t g = 0; g < index.flags.size(); ++g) {
            index.unitMask[g] = before->unitMask[g];
            index.flags[g] |= before->flags[g] & GroupIndex::kOpaqueBlockerTest;
        }
    }
    for (std::size_t i = 0; i < record.samples.size(); ++i)
        if (!before || !(*kept)[i]) AddSampleUnits(record, record.samples[i]);
}

void AddToGroupIndex(BlockRecord &record, const StoredSample &s) {
    AddSampleFlags(record.groupIndex, s);
    AddSampleUnits(record, s);
}

}  // namespace povrayfc
