// ReplayPolicy: keep surface hits, and the shadow tests that light them, only while running
// them again keeps samples.
//
// Keeping them costs every sample traced again (its hits described, its tests kept, 300
// bytes more in the store), and running them again costs nearly what tracing costs; they
// pay where a changed surface ends rays as it did (a face growing or turning in its own
// plane), and waste where what changed is what the rays see (Newton's swinging balls keep
// one sample in a thousand tried). After a frame whose tries kept fewer than
// 1 in kPayingShare, the next kFirstPause frames keep none, then twice as many after each
// such frame again (up to kMaxPause); a frame whose tries pay resets the pause. Counts, not
// time: the same frames keep in every run.
#ifndef POVRAYFC_REPLAY_POLICY_H
#define POVRAYFC_REPLAY_POLICY_H

#include <algorithm>
#include <cstdint>

namespace povrayfc {

class ReplayPolicy {
  public:
    static constexpr std::uint64_t kPayingShare = 4;  // kept * 4 >= tried pays
    static constexpr int kFirstPause = 16, kMaxPause = 128;

    // Whether the frame about to be rendered keeps hits and every shadow test.
    bool Keep() const { return pauseLeft_ == 0; }

    // After a frame: how many dirty samples with hits or tests were tried, and how many of
    // them were kept by their hits or their tests (shadow tests through glass count too:
    // they are tried together).
    void AfterFrame(std::uint64_t tried, std::uint64_t kept) {
        if (pauseLeft_ > 0) {
            --pauseLeft_;
            return;
        }
        if (tried == 0) return;
        if (kept * kPayingShare >= tried) {
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
