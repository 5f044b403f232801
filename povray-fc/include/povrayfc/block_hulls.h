// BlockHulls: which of a frame's changed hulls can reach one stored render block, found
// from the block's cones and loose box before any of its segments is tested.
#ifndef POVRAYFC_BLOCK_HULLS_H
#define POVRAYFC_BLOCK_HULLS_H

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "povrayfc/change_index.h"
#include "povrayfc/segment_fans.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// A change of hundreds of objects (a pattern that moves over many tiles, a flock) spreads
// its hulls over the whole view, so the union box rejects nothing and every segment of
// every block used to walk the change grid. Seen from one block, few of those hulls are
// reachable: its camera rays lie in a narrow cone, its shadow rays in one cone per light.
// Up to kMaxLocal such candidates are kept per block; each fan (and the loose segments)
// gets a bit mask over them, and a segment is tested against its mask's hulls only.
struct BlockHulls {
    using Mask = std::uint64_t;
    static constexpr std::size_t kMaxLocal = 64;
    // Above this many changed hulls, sorting them per block costs more than the grid.
    static constexpr std::size_t kMaxHullsToSort = 512;

    // all: too many candidates to list; test segments against the whole ChangeIndex
    // (whenever their mask below is non-zero).
    bool all = false;
    std::size_t count = 0;
    std::uint32_t local[kMaxLocal];  // candidate number -> index into ChangeIndex::Hulls()
    Mask fan[BlockFans::kMaxFans] = {0};
    Mask loose = 0;      // loose segments of finite length (InLooseBox)
    Mask unbounded = 0;  // loose segments without an end (BlockFans::unbounded)

    // True when some fan or the loose box may reach a change (then segments need testing).
    bool Any() const;
    // True when segment `s` of fan `fanNumber` (BlockFans::kLoose for none) may meet a change:
    // its candidates, then the box around all changes, then the candidates' hulls (as
    // block_tracer.cpp tests a stored sample's segments).
    bool SegmentMayMeet(const Segment &s, std::uint8_t fanNumber, const ChangeIndex &changes) const {
        const Mask mask = MaskOf(s, fanNumber);
        return mask != 0 && changes.UnionClearance(s) == 0.0 && MayMeetHulls(s, mask, changes);
    }
    // The candidates segment `s` of fan `fanNumber` may reach (0: none).
    Mask MaskOf(const Segment &s, std::uint8_t fanNumber) const {
        if (fanNumber != BlockFans::kLoose) return fan[fanNumber];
        return InLooseBox(s) ? loose : unbounded;
    }
    // A segment's bundle class, one of kClassBits bits: fans 0-5 each, the fans from 6 on
    // together, the loose segments of finite length, those without an end (a stored
    // sample keeps which classes it tested in as few bits: sample_store.h).
    static constexpr std::uint32_t kClassBits = 9;
    static constexpr std::uint32_t kLooseClass = std::uint32_t(1) << 7, kUnboundedClass = std::uint32_t(1) << 8;
    static std::uint32_t FanClass(std::size_t fanNumber) { return std::uint32_t(1) << std::min<std::size_t>(fanNumber, 6); }
    static std::uint32_t ClassBit(const Segment &s, std::uint8_t fanNumber) {
        if (fanNumber != BlockFans::kLoose) return FanClass(fanNumber);
        return InLooseBox(s) ? kLooseClass : kUnboundedClass;
    }
    // The classes of the bundles whose mask is not 0.
    std::uint32_t ReachedClasses() const;
    // True when segment `s`, whose MaskOf is `mask` (not 0), may meet one of those
    // candidates (or any change, when `all`): the part of SegmentMayMeet after the union box.
    bool MayMeetHulls(const Segment &s, Mask mask, const ChangeIndex &changes) const;
};

// The candidates of a block whose fans are built (BlockRecord::fans).
BlockHulls FindBlockHulls(const BlockFans &fans, const ChangeIndex &changes);
// The candidates of one group of the block's samples (BlockRecord::groupFans), among
// those of the block.
BlockHulls FindGroupHulls(const BlockFans &group, const ChangeIndex &changes, const BlockHulls &block);

}  // namespace povrayfc

#endif
