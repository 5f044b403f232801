// The render settings of one frame that decide whether its pixels can come from the last.
#ifndef POVRAYFC_FRAME_SETUP_H
#define POVRAYFC_FRAME_SETUP_H

#include <cstdint>
#include <string>

namespace povrayfc {

struct FrameSetup {
    // Frame_Coherence_Grid's range: 0 (automatic) to this many voxels along the change
    // index's longest axis (256^3 voxels of 4-byte offsets is 64 MiB).
    static constexpr int kMaxGridResolution = 256;

    int width = 0, height = 0;                 // the whole image
    int left = 0, top = 0, right = -1, bottom = -1;  // render area, inclusive, 0-based
    int samplingMethod = 0;                    // 0 no anti-aliasing, 1 or 2: POV-Ray's +AM
    int blockSize = 32;                        // +BS: AA method 1 pixels depend on the block grid
    // Everything else of the render options that can change a pixel (quality, AA depth,
    // threshold, jitter, gamma, ...), hashed by the caller; a change starts a new sequence.
    std::uint64_t optionsHash = 0;

    // Per-frame facts.
    int frameNumber = 0;
    double clock = 0.0;
    bool mosaicPreview = false;   // +SP/+EP: traces pixels at several sizes
    bool continueTrace = false;   // +C
    bool sceneCameraOverride = false;  // camera set by the front end, not the scene
    // The front end shows no display, so its image keeps every pixel it was last sent:
    // blocks reused whole need not be sent again.
    bool frontEndKeepsImage = false;
    int renderThreads = 1;        // +WT: effects with per-thread random sequences are
                                  // reproducible only with one

    // Options of fc itself.
    int gridResolution = 0;       // voxels of the change index along its longest axis; 0 = automatic
    // Frame_Coherence_Memory (given in MiB): the most the store may hold, in bytes; 0 = the
    // default (half of the machine's memory). Blocks past it are traced in full.
    std::uint64_t memoryBudgetBytes = 0;
    std::string statsFile;        // per-frame CSV, empty for none
    std::string maskDir;          // folder for per-frame re-traced pixel masks, empty for none

    int AreaWidth() const { return right - left + 1; }
    int AreaHeight() const { return bottom - top + 1; }
};

// Mixes a value into a running hash (for FrameSetup::optionsHash).
inline std::uint64_t MixOption(std::uint64_t hash, double value) {
    std::uint64_t bits;
    static_assert(sizeof bits == sizeof value, "double is 64-bit");
    __builtin_memcpy(&bits, &value, sizeof bits);
    hash ^= bits + 0x9E3779B97F4A7C15ull + (hash << 6) + (hash >> 2);
    return hash * 0xff51afd7ed558ccdull;
}

// Effects of the parsed scene that only the render side can see.
struct SceneEffects {
    bool radiosity = false;
    bool photons = false;
    bool subsurface = false;
    bool jitteredAreaLight = false;
};

}  // namespace povrayfc

#endif
