// UnitIds: the numbers recorded segments know the units they ended on by, kept from frame
// to frame.
//
// The parser numbers a frame's units afresh (scene_signature.h). A recorded segment must
// name its unit in a way the next frames still understand, so each unit gets an id that it
// keeps for as long as it stays unchanged. A changed or vanished unit's id dirties, in
// that frame, every sample with a segment that ended on it; those samples are traced again
// in that frame (or their block is forgotten), so from the next frame on nothing refers
// to the id and it is given to another unit. A unit whose texture alone changed keeps its
// id (samples whose shadow tests its opaque surfaces answered stay valid and still name
// it). Ids therefore stay dense, and a frame's changed units are a flat table lookup away.
#ifndef POVRAYFC_UNIT_IDS_H
#define POVRAYFC_UNIT_IDS_H

#include <cstdint>
#include <vector>

namespace povrayfc {

class UnitIds {
  public:
    static constexpr std::uint32_t kNone = 0xffffffffu;

    // A new sequence (or a frame traced in full): this frame's `unitCount` units get the ids
    // 0 .. unitCount-1, and no earlier id is in use.
    void Reset(std::size_t unitCount);
    // The next frame of a sequence: unit i keeps the id of the last frame's unit
    // continues[i] (kNone: it is new), the others get free ids; the ids of the last frame's
    // units in `vanished` (their indices in that frame) are appended to `changedIds`, and
    // those no unit continues are given up.
    void Advance(const std::vector<std::uint32_t> &continues, const std::vector<std::uint32_t> &vanished,
                 std::vector<std::uint32_t> &changedIds);
    // The id the last frame's unit `last` had before the latest Advance (kNone when unknown).
    std::uint32_t Previous(std::uint32_t last) const { return last < previous_.size() ? previous_[last] : kNone; }

    // This frame's id of each unit, by the parser's index.
    const std::vector<std::uint32_t> &Current() const { return current_; }
    // Every id in use is below this.
    std::uint32_t Limit() const { return limit_; }

  private:
    std::uint32_t Take();

    std::vector<std::uint32_t> current_;
    std::vector<std::uint32_t> previous_;
    std::vector<std::uint32_t> free_;      // may be given out this frame
    std::vector<std::uint32_t> released_;  // given up this frame: free from the next
    std::uint32_t limit_ = 0;
};

}  // namespace povrayfc

#endif
