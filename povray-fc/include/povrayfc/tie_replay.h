// Tied searches run again: a sample whose nearest hit was decided by the order of the
// scene's objects (tie_watch.h) is kept in a frame with a new order when POV-Ray, asked the
// same searches again in that frame, finds the same answers.
//
// Why it is exact. A sample's trace is a sequence of searches for a nearest intersection;
// each search's ray and bound follow from the searches before it. A search that was not
// tied found the one candidate nearest along its ray whatever order the candidates came
// in, so in a frame where its segment meets no change it finds the same again. A tied
// search is kept with its ray exactly as traced (doubles), POV-Ray's ray flags, the
// conditions it searched with, the bound it started from, and what it found: the unit of
// the object, that object's own hash (two parts of one unit are told apart), and the
// depth. When every segment of the sample is clean, the searches are run again in the
// sample's order through POV-Ray's own search in this frame: if each finds the same
// object at the same depth, every ray after it is the one traced before, by induction
// the whole trace is, and so is the colour. One that finds anything else, or a search fc
// could not describe (another kind of search, too many), makes the sample dirty.
//
// The answer is compared as (unit id, object hash, depth): two objects with the same unit
// and hash were parsed from the same tokens with the same values, so which of them is hit
// at one depth makes no difference to the colour.
#ifndef POVRAYFC_TIE_REPLAY_H
#define POVRAYFC_TIE_REPLAY_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

// One search for a ray's nearest intersection, and what it found. Plain data (no
// initialisers): filled by a TieWatch and its describer when the search ended in a tie.
struct TiedSearch {
    std::uint8_t kind;          // the conditions it searched with; the patch layer numbers them
    std::uint16_t rayFlags;     // POV-Ray's flags of the ray (image, reflection, shadow test, ...)
    double origin[3];
    double direction[3];
    double start;               // the depth the search started from (its bound)
    double depth;               // the depth it ended with (start when it found nothing)
    std::uint32_t unit;         // what it found: a unit id (unit_ids.h), or Segment::kNoUnit
    std::uint64_t objectHash;   // that object's own hash
};

// The search again, in the frame being rendered: implemented by the patch layer with
// POV-Ray's own search. `unitIndex` is the index the parser wrote into the object found
// (kUnitNothing when none). False when the search cannot be run as described.
class TieReplayer {
  public:
    virtual ~TieReplayer() = default;
    virtual bool Replay(const TiedSearch &search, double &depth, std::uint32_t &unitIndex,
                        std::uint64_t &objectHash) = 0;
};

// The searches a sample keeps are packed after its segments in BlockRecord::packed:
//   count (1 byte: how many follow, or kTiesUnknown when they cannot be replayed)
//   per search: kind (1), ray flags (2), origin and direction (6 doubles), start and depth
//   (2 doubles), unit (4), object hash (8): kTiedSearchBytes
constexpr std::uint8_t kTiesUnknown = 0xff;
constexpr std::size_t kMaxTiedSearches = 64;
constexpr std::size_t kTiedSearchBytes = 1 + 2 + 8 * 8 + 4 + 8;

// Appends `searches` (or, when !complete, the mark that they cannot be replayed).
void PackTiedSearches(const std::vector<TiedSearch> &searches, bool complete, std::vector<std::uint8_t> &packed);
// The bytes PackTiedSearches wrote at `bytes`.
std::size_t TiedSearchesBytes(const std::uint8_t *bytes);
// Reads them back; false when they were marked as not replayable.
bool UnpackTiedSearches(const std::uint8_t *bytes, std::vector<TiedSearch> &searches);

// Runs the packed searches at `bytes` again through `replayer`, in order, and says whether
// each found what it found before; it stops at the first that did not. `unitIds` maps this
// frame's unit indexes to ids (FramePlan::unitIds).
bool TiedSearchesHold(const std::uint8_t *bytes, TieReplayer *replayer, const std::uint32_t *unitIds,
                      std::size_t unitCount);

}  // namespace povrayfc

#endif
