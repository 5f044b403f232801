// Formatting of frame-coherence statistics.
#include "povrayfc/frame_stats.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace povrayfc {

namespace {
std::string CsvQuoted(const std::string &s) {
    std::string out = "\"";
    for (char c : s) out += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}
}  // namespace

std::string FrameStats::LogLine() const {
    char buf[512];
    const double percent = pixels ? 100.0 * double(traced) / double(pixels) : 0.0;
    std::snprintf(buf, sizeof buf,
                  "Frame coherence: frame %d: %llu of %llu pixels traced (%.1f%%), %llu reused, "
                  "%llu samples traced, %llu reused, %llu changed units, %llu new shapes, bookkeeping %.3f s, store %.1f MiB",
                  frame, (unsigned long long)traced, (unsigned long long)pixels, percent,
                  (unsigned long long)reused, (unsigned long long)samplesTraced,
                  (unsigned long long)samplesReused, (unsigned long long)changedUnits, (unsigned long long)changedHulls,
                  bookkeepingSeconds,
                  double(storeBytes) / 1048576.0);
    std::string line = buf;
    if (overBudgetBlocks > 0)
        line += "; " + std::to_string(overBudgetBlocks) + " blocks past Frame_Coherence_Memory, traced in full when next rendered";
    if (!fullReason.empty()) line += "; full frame: " + fullReason;
    return line;
}

std::string FrameStats::CsvHeader() {
    return "frame,clock,coherent,full_reason,pixels,traced,reused,changed_hulls,samples_traced,"
           "samples_reused,rays,bookkeeping_s,store_bytes,render_s,samples_tested,samples_cleared,changed_units,"
           "over_budget_blocks,tied_samples_replayed,tied_samples_kept,replay_samples_tried,shadow_samples_kept,surface_samples_kept";
}

std::string FrameStats::CsvRow() const {
    std::ostringstream row;
    row.precision(17);
    row << frame << ',' << clock << ',' << (coherent ? 1 : 0) << ',' << CsvQuoted(fullReason)
        << ',' << pixels << ',' << traced << ',' << reused << ',' << changedHulls << ',' << samplesTraced << ',' << samplesReused
        << ',' << rays << ',' << bookkeepingSeconds << ',' << storeBytes << ',' << renderSeconds << ','
        << samplesTested << ',' << samplesCleared << ',' << changedUnits << ',' << overBudgetBlocks << ','
        << tiedSamplesReplayed << ',' << tiedSamplesKept << ',' << replaySamplesTried << ',' << shadowSamplesKept << ',' << surfaceSamplesKept;
    return row.str();
}

bool AppendStatsCsv(const std::string &path, const FrameStats &stats, std::string &error) {
    std::FILE *f = std::fopen(path.c_str(), "a");
    if (!f) {
        error = path + ": " + std::strerror(errno);
        return false;
    }
    std::fseek(f, 0, SEEK_END);
    const bool empty = std::ftell(f) == 0;
    std::string text = (empty ? FrameStats::CsvHeader() + "\n" : std::string()) + stats.CsvRow() + "\n";
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) {
        error = path + ": " + std::strerror(errno);
        return false;
    }
    return true;
}

}  // namespace povrayfc
