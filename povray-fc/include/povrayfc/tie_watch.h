// TieWatch: whether a search for a ray's nearest intersection found an answer that
// depends on the order in which POV-Ray tried the objects.
//
// POV-Ray keeps the first of two intersections at exactly the same depth (coincident
// surfaces: a label flush with a wall, two copies of an object left in place). Which one
// comes first depends on the whole scene, not on the ray: the bounding tree, rebuilt
// every frame over every finite object, and the order of the objects in the scene. The
// tree also decides which nearly-tied candidates are tried at all: a box entered a hair
// after the best depth found so far is skipped, and POV-Ray's float boxes are rounded to
// nearest, so an object can reach a hair outside its own box.
//
// A sample one of whose searches ended in such a tie is "order-sensitive" (its recorder
// is told). In a frame whose ordered list of objects differs from the last frame's
// (anything that changes, appears, vanishes or moves in the list can reshape the tree),
// such a sample none of whose segments meets a change has its tied searches run again
// (tie_replay.h) and is kept when they find what they found; a search the hooks did not
// describe cannot be run again, and its sample is traced again in every such frame. Ties
// are rare, so this costs next to nothing where there are none.
//
// The search hooks call this as follows (one per scene-level search, on the stack):
//
//   TieWatch watch(ray.Direction, bestisect.Depth);   // judges when it goes out of scope
//   ... for every object the search intersects:  NoteTieCandidate(depth)
//   ... when it stops at a box or cell it does not enter: NoteTieSkipped(entry, magnitude)
//   if (TieSearchTied()) {             // the search done, before the watch goes
//       DescribeTieSearch(kind, flags, ray.Origin);   // to run it again (tie_replay.h)
//       NoteTieSearchFound(unit, hash);               // and what it found
//   }
//
// The notes reach the innermost watch of the thread. Every call is one thread-local test
// when the thread is not recording a sample.
#ifndef POVRAYFC_TIE_WATCH_H
#define POVRAYFC_TIE_WATCH_H

#include <cmath>
#include <limits>

#include "povrayfc/ray_recording.h"
#include "povrayfc/tie_replay.h"

namespace povrayfc {

class TieWatch;

namespace detail {
extern thread_local TieWatch *tlsTieWatch;
}  // namespace detail

class TieWatch {
  public:
    // `best`: the search's best depth, read when the watch is destroyed (the search's
    // result by then; its starting value bounds the search, e.g. a shadow ray's light).
    // Not recording (every ray with fc off, and most without a sample open), the watch
    // costs one thread-local load here and a test when it goes: nothing else is set.
    TieWatch(const double direction[3], const double &best) : recorder_(detail::tlsRecorder), best_(best) {
        if (!recorder_) return;
        outer_ = detail::tlsTieWatch;
        direction_[0] = direction[0];
        direction_[1] = direction[1];
        direction_[2] = direction[2];
        nearest_ = second_ = skippedReach_ = std::numeric_limits<double>::infinity();
        search_.start = best;
        described_ = found_ = false;
        // The thread's innermost watch until the destructor restores the outer one.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdangling-pointer"
#endif
        detail::tlsTieWatch = this;
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic pop
#endif
    }
    ~TieWatch() {
        if (!recorder_) return;
        detail::tlsTieWatch = outer_;
        if (!Tied(best_)) return;
        if (described_ && found_) {
            search_.depth = best_;
            recorder_->AddTiedSearch(search_, foundUnit_);
        } else {
            recorder_->MarkOrderSensitive();
        }
    }
    TieWatch(const TieWatch &) = delete;
    TieWatch &operator=(const TieWatch &) = delete;

    // What the search is, to run it again (tie_replay.h): the conditions it searches with
    // (`kind`, numbered by the caller), the ray's flags, and its origin (the direction was
    // given to the constructor).
    void Describe(std::uint8_t kind, std::uint16_t rayFlags, const double origin[3]) {
        if (!recorder_) return;
        search_.kind = kind;
        search_.rayFlags = rayFlags;
        for (int i = 0; i < 3; ++i) {
            search_.origin[i] = origin[i];
            search_.direction[i] = direction_[i];
        }
        described_ = true;
    }
    // What the search found: the unit index the parser wrote into the object (kUnitNothing
    // when none) and the object's own hash. Call after the search, before the watch goes.
    void Found(std::uint32_t unitIndex, std::uint64_t objectHash) {
        if (!recorder_) return;
        foundUnit_ = unitIndex;
        search_.objectHash = objectHash;
        found_ = true;
    }

    // An object's nearest intersection at `depth`, whether or not it became the best.
    void Candidate(double depth) {
        if (depth < nearest_) {
            second_ = nearest_;
            nearest_ = depth;
        } else if (depth < second_) {
            second_ = depth;
        }
    }
    // The search stopped before a bounding box or cell it would enter at `entry`, whose
    // bounds are float coordinates of at most `magnitude` (the scene's extent will do).
    void Skipped(double entry, double magnitude) {
        const double reach = entry - SkipSlack(magnitude);
        if (reach < skippedReach_) skippedReach_ = reach;
    }

    // Whether the search, ending with best depth `best`, may have depended on the order of
    // its candidates: two candidates tied at the best depth, or something skipped close
    // enough behind it that its object may reach up to the best depth.
    bool Tied(double best) const { return (nearest_ == best && second_ == best) || skippedReach_ <= best; }
    // The same for the search's best depth as it stands (its result, once it is done).
    bool Tied() const { return Tied(best_); }

    // How far before its entry depth a skipped box's object may intersect the ray. A leaf's
    // float box is within 2^-23 of `magnitude` of the object's exact box (its corner and
    // its lengths are each rounded to nearest), and every enclosing node's box rounds its
    // lengths once more; along the ray that is as much divided by the smallest non-zero
    // direction component (a ray crossing a face at a grazing angle travels far for a
    // small step across it). 2^-18 covers 32 levels of nodes (POV-Ray's tree branches four
    // ways: 32 levels hold 2^64 objects). A wider slack would mark samples near every
    // contact between objects, which are traced again whenever anything moves.
    double SkipSlack(double magnitude) const {
        double smallest = std::numeric_limits<double>::infinity();
        for (double d : direction_) {
            const double a = std::fabs(d);
            if (a > 0.0 && a < smallest) smallest = a;
        }
        if (!(smallest < std::numeric_limits<double>::infinity())) return std::numeric_limits<double>::infinity();
        return std::ldexp(std::fabs(magnitude), -18) / smallest;
    }

  private:
    SampleRecorder *recorder_;
    const double &best_;
    // Set only while recording (see the constructor).
    TieWatch *outer_;
    double direction_[3];
    double nearest_, second_, skippedReach_;
    TiedSearch search_;
    std::uint32_t foundUnit_;
    bool described_, found_;
};

// From the hooks inside a search (see above): no-ops unless a watch is open on this thread.
inline bool TieWatchOpen() { return detail::tlsTieWatch != nullptr; }
inline void NoteTieCandidate(double depth) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Candidate(depth);
}
inline void NoteTieSkipped(double entry, double magnitude) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Skipped(entry, magnitude);
}
// From the hook that describes a search (fc-scene's tie_searches.h), once the search is
// done: whether the innermost watch's search ended in a tie; if so, what it is and what
// it found (TieWatch::Describe, Found). Only a tied search is described, so the hooks cost
// next to nothing on every other.
inline bool TieSearchTied() { return detail::tlsTieWatch != nullptr && detail::tlsTieWatch->Tied(); }
inline void DescribeTieSearch(std::uint8_t kind, std::uint16_t rayFlags, const double origin[3]) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Describe(kind, rayFlags, origin);
}
inline void NoteTieSearchFound(std::uint32_t unitIndex, std::uint64_t objectHash) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Found(unitIndex, objectHash);
}
// The same for a skipped float box as POV-Ray keeps it (lower corner and lengths); it holds
// the boxes below it, so its magnitude bounds theirs.
inline void NoteTieSkippedBox(double entry, const float lowerLeft[3], const float lengths[3]) {
    if (!detail::tlsTieWatch) return;
    double magnitude = 0.0;
    for (int i = 0; i < 3; ++i)
        magnitude = std::fmax(magnitude, std::fmax(std::fabs(double(lowerLeft[i])),
                                                   std::fabs(double(lowerLeft[i]) + double(lengths[i]))));
    detail::tlsTieWatch->Skipped(entry, magnitude);
}
// The same for a skipped region with double bounds (a BSP tree's).
inline void NoteTieSkippedBounds(double entry, const double lower[3], const double upper[3]) {
    if (!detail::tlsTieWatch) return;
    double magnitude = 0.0;
    for (int i = 0; i < 3; ++i) magnitude = std::fmax(magnitude, std::fmax(std::fabs(lower[i]), std::fabs(upper[i])));
    detail::tlsTieWatch->Skipped(entry, magnitude);
}

}  // namespace povrayfc

#endif
