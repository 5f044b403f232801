// BlockHulls: per-block candidate hulls from the block's cones and loose box.
#include "povrayfc/block_hulls.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "povrayfc/hull.h"
#include "povrayfc/segment_fans.h"

namespace povrayfc {

namespace {

// Whether a hull's box comes near the loose segments of finite length: their box, widened
// by a margin larger than twice the rounding margin of any segment inside it against any
// hull inside the change's union (the scale is the union's, so one margin serves all).
struct LooseReach {
    Box box;
    double margin = 0.0;
    bool finite = false;

    LooseReach(const BlockFans &fans, const Box &changed) : box(fans.looseBox) {
        if (box.Empty()) return;
        finite = box.IsFinite() && changed.IsFinite();
        double scale = 0;
        for (int a = 0; a < 3; ++a)
            scale = std::max({scale, std::fabs(box.lo[a]), std::fabs(box.hi[a]), std::fabs(changed.lo[a]),
                              std::fabs(changed.hi[a])});
        margin = 0x1p-16 * scale + 1e-30;
    }
    bool Empty() const { return box.Empty(); }
    bool Meets(const Box &u) const {
        if (box.Empty()) return false;
        if (!finite || !u.IsFinite()) return true;
        const double m = margin;
        return box.lo.x <= u.hi.x + m && u.lo.x <= box.hi.x + m && box.lo.y <= u.hi.y + m &&
               u.lo.y <= box.hi.y + m && box.lo.z <= u.hi.z + m && u.lo.z <= box.hi.z + m;
    }
};

}  // namespace

bool BlockHulls::Any() const {
    if (loose || unbounded) return true;
    for (Mask m : fan)
        if (m) return true;
    return false;
}

std::uint32_t BlockHulls::ReachedClasses() const {
    std::uint32_t set = (loose ? kLooseClass : 0) | (unbounded ? kUnboundedClass : 0);
    for (std::size_t f = 0; f < BlockFans::kMaxFans; ++f)
        if (fan[f]) set |= FanClass(f);
    return set;
}

bool BlockHulls::MayMeetHulls(const Segment &s, Mask mask, const ChangeIndex &changes) const {
    // (The union test comes first, in the caller: it rejects most segments of a wide fan at
    // the price of one.)
    if (all) return changes.MayMeet(s);
    for (; mask; mask &= mask - 1)
        if (changes.MayMeetHull(s, local[std::size_t(__builtin_ctzll(mask))])) return true;
    return false;
}

namespace {

// The candidates among `candidates` (indices into changes.Hulls(); null: all of them) that
// the cones `blockFans` reach.
BlockHulls FindHulls(const BlockFans &blockFans, const ChangeIndex &changes, const std::uint32_t *candidates,
                     std::size_t candidateCount) {
    BlockHulls result;
    const std::vector<SegmentFan> &fans = blockFans.fans;
    Hull everything;
    everything.box = changes.Bounds();
    const LooseReach looseReach(blockFans, changes.Bounds());

    // Each cone's trigonometry once for all the hulls (only cones with segments).
    std::optional<FanTester> tester[BlockFans::kMaxFans], unboundedTester;
    bool fanReaches[BlockFans::kMaxFans] = {false};
    bool anyReach = false;
    for (std::size_t f = 0; f < fans.size(); ++f) {
        if (fans[f].reach < 0) continue;
        tester[f].emplace(fans[f]);
        anyReach |= fanReaches[f] = tester[f]->MayMeet(everything);
    }
    const bool looseReaches = looseReach.Meets(changes.Bounds());
    if (blockFans.unbounded.reach >= 0) unboundedTester.emplace(blockFans.unbounded);
    const bool unboundedReaches = unboundedTester && unboundedTester->MayMeet(everything);
    if (!anyReach && !looseReaches && !unboundedReaches) return result;

    auto everythingReachable = [&] {
        result.all = true;
        for (std::size_t f = 0; f < fans.size(); ++f) result.fan[f] = fanReaches[f] ? 1 : 0;
        result.loose = looseReaches ? 1 : 0;
        result.unbounded = unboundedReaches ? 1 : 0;
        return result;
    };
    if (!candidates && changes.HullCount() > BlockHulls::kMaxHullsToSort) return everythingReachable();

    const std::vector<Hull> &hulls = changes.Hulls();
    const std::size_t count = candidates ? candidateCount : hulls.size();
    for (std::size_t c = 0; c < count; ++c) {
        const std::uint32_t h = candidates ? candidates[c] : std::uint32_t(c);
        // bit f: fan f; bit kMaxFans: the loose box; bit kMaxFans + 1: the unbounded cone
        BlockHulls::Mask reachedBy = 0;
        const BlockHulls::Mask looseBit = BlockHulls::Mask(1) << BlockFans::kMaxFans, unboundedBit = looseBit << 1;
        for (std::size_t f = 0; f < fans.size(); ++f)
            if (fanReaches[f] && tester[f]->MayMeet(hulls[h])) reachedBy |= BlockHulls::Mask(1) << f;
        if (looseReaches && looseReach.Meets(hulls[h].box)) reachedBy |= looseBit;
        if (unboundedReaches && unboundedTester->MayMeet(hulls[h])) reachedBy |= unboundedBit;
        if (!reachedBy) continue;
        if (result.count == BlockHulls::kMaxLocal) return everythingReachable();
        const BlockHulls::Mask bit = BlockHulls::Mask(1) << result.count;
        result.local[result.count++] = h;
        for (std::size_t f = 0; f < fans.size(); ++f)
            if (reachedBy & (BlockHulls::Mask(1) << f)) result.fan[f] |= bit;
        if (reachedBy & looseBit) result.loose |= bit;
        if (reachedBy & unboundedBit) result.unbounded |= bit;
    }
    return result;
}

}  // namespace

BlockHulls FindBlockHulls(const BlockFans &fans, const ChangeIndex &changes) {
    return FindHulls(fans, changes, nullptr, 0);
}

BlockHulls FindGroupHulls(const BlockFans &group, const ChangeIndex &changes, const BlockHulls &block) {
    if (!block.Any()) return BlockHulls();
    // A group's segments are some of the block's: only the block's candidates can reach
    // them (all of them when the block listed none).
    return block.all ? FindHulls(group, changes, nullptr, 0) : FindHulls(group, changes, block.local, block.count);
}

}  // namespace povrayfc
