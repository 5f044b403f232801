// GroupFans: per-group cones of a block's samples, built and grown, and the block's
// cones merged from them.
#include "povrayfc/group_fans.h"

namespace povrayfc {

void BuildRecordFans(BlockRecord &record) {
    ValidateFanNumbers(record.fanOf, record.apexes);
    thread_local std::vector<std::vector<std::uint32_t>> members;
    members.resize(record.GroupCount());
    for (std::vector<std::uint32_t> &m : members) m.clear();
    for (const StoredSample &s : record.samples) {
        if (s.segmentCount == StoredSample::kEverything) continue;
        std::vector<std::uint32_t> &m = members[s.group];
        for (std::uint32_t k = 0; k < s.segmentCount; ++k) m.push_back(s.firstSegment + k);
    }
    record.groupFans.clear();
    record.groupFans.reserve(record.GroupCount());
    for (std::size_t g = 0; g < record.GroupCount(); ++g)
        record.groupFans.push_back(BuildFansOf(record.segments.data(), record.fanOf.data(), record.apexes, members[g]));
    record.fans = MergeFans(record.groupFans, record.apexes);
    record.fansBuilt = true;
}

void GrowRecordFans(BlockRecord &record, const std::vector<std::pair<std::size_t, std::size_t>> &added,
                    const std::vector<std::uint32_t> &addedGroup) {
    thread_local std::vector<std::vector<std::pair<std::size_t, std::size_t>>> addedTo;
    addedTo.resize(record.groupFans.size());
    for (auto &a : addedTo) a.clear();
    for (std::size_t i = 0; i < added.size(); ++i) {
        addedTo[addedGroup[i]].push_back(added[i]);
        // The kept segments' numbers were made valid when the cones were built.
        for (std::size_t k = added[i].first; k < added[i].first + added[i].second; ++k)
            if (record.fanOf[k] >= record.apexes.count) record.fanOf[k] = BlockFans::kLoose;
    }
    for (std::size_t g = 0; g < record.groupFans.size(); ++g)
        if (!addedTo[g].empty())
            record.groupFans[g] = GrowFans(record.groupFans[g], record.segments.data(), record.fanOf.data(),
                                           record.apexes, addedTo[g]);
    record.fans = MergeFans(record.groupFans, record.apexes);
    record.fansBuilt = true;
}

}  // namespace povrayfc
