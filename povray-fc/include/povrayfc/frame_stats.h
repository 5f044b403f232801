// Per-frame statistics of frame coherence: the log line and the machine-readable CSV row.
#ifndef POVRAYFC_FRAME_STATS_H
#define POVRAYFC_FRAME_STATS_H

#include <cstdint>
#include <string>

namespace povrayfc {

struct FrameStats {
    int frame = 0;
    double clock = 0.0;
    bool coherent = false;        // fc active: some pixels could be reused
    std::string fullReason;       // why every pixel was traced; empty when fc re-traced a subset
    std::uint64_t pixels = 0;     // pixels in the render area
    std::uint64_t traced = 0;     // pixels with at least one camera sample traced
    std::uint64_t reused = 0;     // pixels made only of stored samples (or stored whole)
    std::uint64_t changedHulls = 0;    // new shapes the stored samples' segments were tested against
    std::uint64_t changedUnits = 0;    // units that changed or vanished: what a segment ended on
    std::uint64_t samplesTraced = 0;   // camera samples traced (AA samples included)
    std::uint64_t samplesReused = 0;   // camera samples whose stored colour was reused
    // Stored samples a change's cones reached: tested segment by segment, or found clean by
    // the clearance kept from an earlier frame (change_drift.h).
    std::uint64_t samplesTested = 0, samplesCleared = 0;
    // Order-sensitive samples clean but for the order of the objects (their tied searches
    // are run again where they could be kept: tie_replay.h), and those of them kept.
    std::uint64_t tiedSamplesReplayed = 0, tiedSamplesKept = 0;
    // Samples dirty with surface hits or shadow tests kept to be run again, and those the
    // run kept: by their shadow tests, and by their surface hits alone (shadow_replay.h,
    // surface_replay.h).
    std::uint64_t replaySamplesTried = 0, shadowSamplesKept = 0, surfaceSamplesKept = 0;
    std::uint64_t rays = 0;       // rays traced (POV-Ray's "Rays:" count)
    double bookkeepingSeconds = 0.0;  // change detection and statistics, outside the render threads
    std::uint64_t storeBytes = 0;     // stored samples, segments and pixels
    std::uint64_t overBudgetBlocks = 0;  // blocks the memory budget left out of the store
    double renderSeconds = 0.0;       // wall time from fc's frame start to its end (tracing)

    // One human-readable line for the render log.
    std::string LogLine() const;
    static std::string CsvHeader();
    std::string CsvRow() const;
};

// Appends `stats` as a CSV row to `path`, writing the header first when the file is new
// or empty. Returns false (and leaves `error` set) when the file cannot be written.
bool AppendStatsCsv(const std::string &path, const FrameStats &stats, std::string &error);

}  // namespace povrayfc

#endif
