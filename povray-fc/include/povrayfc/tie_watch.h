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
//   TieWatch watch(ray.Direction, bestisect.Depth, describe, context);
//                                       // judges when it goes out of scope; describes
//                                       // the search through `describe` if it was tied
//   ... for every object the search intersects:  NoteTieCandidate(depth)
//   ... when it stops at a box or cell it does not enter: NoteTieSkipped(entry, magnitude)
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

// Says what a search that ended in a tie was and what it found, so that it can be run
// again (tie_replay.h): fills `search`'s kind, ray flags, origin and object hash, and the
// unit index the parser wrote into the object found (kUnitNothing: none). False when the
// search cannot be described. `context` is what the hook gave the watch.
using TieDescriber = bool (*)(const void *context, TiedSearch &search, std::uint32_t &unitIndex);

namespace detail {
extern thread_local TieWatch *tlsTieWatch;
}  // namespace detail

class TieWatch {
  public:
    // `direction`: the ray's, which must outlive the watch. `best`: the search's best
    // depth, read when the watch is destroyed (the search's result by then; its starting
    // value bounds the search, e.g. a shadow ray's light).
    // `describe` (with `context`), when given, is asked about the search only if it ends in
    // a tie; without it a tied search cannot be run again.
    // Not recording (every ray with fc off, and most without a sample open), the watch
    // costs one thread-local load here and a test when it goes: nothing else is set.
    TieWatch(const double direction[3], const double &best, TieDescriber describe = nullptr,
             const void *context = nullptr)
        : recorder_(detail::tlsRecorder), best_(best) {
        if (!recorder_) return;
        outer_ = detail::tlsTieWatch;
        direction_ = direction;
        nearest_ = second_ = skippedReach_ = std::numeric_limits<double>::infinity();
        start_ = best;
        describe_ = describe;
        context_ = context;
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
        TiedSearch search;
        std::uint32_t unitIndex;
        if (describe_ && describe_(context_, search, unitIndex)) {
            for (int i = 0; i < 3; ++i) search.direction[i] = direction_[i];
            search.start = start_;
            search.depth = best_;
            recorder_->AddTiedSearch(search, unitIndex);
        } else {
            recorder_->MarkOrderSensitive();
        }
    }
    TieWatch(const TieWatch &) = delete;
    TieWatch &operator=(const TieWatch &) = delete;

    // Whether the thread records a sample: otherwise the watch does nothing, and what a
    // describer would read need not be kept.
    bool Recording() const { return recorder_ != nullptr; }

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
        for (int i = 0; i < 3; ++i) {
            const double a = std::fabs(direction_[i]);
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
    const double *direction_;  // the ray's, which outlives the search
    double nearest_, second_, skippedReach_;
    double start_;  // the best depth the search started from
    TieDescriber describe_;
    const void *context_;
};

// From the hooks inside a search (see above): no-ops unless a watch is open on this thread.
inline bool TieWatchOpen() { return detail::tlsTieWatch != nullptr; }
inline void NoteTieCandidate(double depth) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Candidate(depth);
}
inline void NoteTieSkipped(double entry, double magnitude) {
    if (detail::tlsTieWatch) detail::tlsTieWatch->Skipped(entry, magnitude);
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
