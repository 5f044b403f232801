// ReplayPolicy: keep surface hits, and the shadow tests that light them, only while running
// them again saves more than it costs.
//
// Keeping them costs every sample traced again (its hits described, its tests kept, 300
// bytes more in the store), and running them again costs a search or a shadow test each:
// about a ray, and a hit's signature about as much as shading it. A kept sample saves the
// rays it would have traced, about its segments. Where a sample is a camera ray and a
// shadow test (Debian's float4, whose turning box face keeps half its samples this way)
// running them again costs what tracing does, and the bookkeeping more; where what changed
// is what the rays see (Newton's swinging balls), almost nothing is kept. So after a frame
// whose kept samples' segments were fewer than kSavedPerRun times the runs it made, the
// next kFirstPause frames keep none, then twice as many after each such frame again (up to
// kMaxPause); a frame that pays resets the pause. Counts, not time: the same frames keep in
// every run.
#ifndef POVRAYFC_REPLAY_POLICY_H
#define POVRAYFC_REPLAY_POLICY_H

#include <algorithm>
#include <cstdint>

namespace povrayfc {

class ReplayPolicy {
  public:
    static constexpr std::uint64_t kSavedPerRun = 4;  // kept segments >= 4 * runs pays
    static constexpr int kFirstPause = 16, kMaxPause = 128;

    // Whether the frame about to be rendered keeps hits and every shadow test.
    bool Keep() const { return pauseLeft_ == 0; }

    // After a frame: how many searches and shadow tests it ran again, and how many segments
    // the samples that kept were (shadow tests through glass count too: they are tried
    // together).
    void AfterFrame(std::uint64_t runs, std::uint64_t keptSegments) {
        if (pauseLeft_ > 0) {
            --pauseLeft_;
            return;
        }
        if (runs == 0) return;
        if (keptSegments >= kSavedPerRun * runs) {
            nextPause_ = kFirstPause;
            return;
        }
        pauseLeft_ = nextPause_;
        nextPause_ = std::min(2 * nextPause_, kMaxPause);
    }
    void Reset() {
        pauseLeft_ = 0;
        nextPause_ = kFirstPause;
    }

  private:
    int pauseLeft_ = 0;
    int nextPause_ = kFirstPause;
};

}  // namespace povrayfc

#endif
