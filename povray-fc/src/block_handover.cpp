// BlockHandover: a tile's stored blocks, out of one renderer and into another.
#include "povrayfc/block_handover.h"

#include <cstring>
#include <type_traits>

namespace povrayfc {

namespace {

constexpr char kMagic[8] = {'P', 'F', 'C', 'H', 'A', 'N', 'D', '1'};

static_assert(std::is_trivially_copyable<StoredSample>::value, "samples are copied raw");
static_assert(std::is_trivially_copyable<Segment>::value, "segments are copied raw");
static_assert(std::is_trivially_copyable<FanApexes>::value, "apexes are copied raw");

template <typename T>
void Put(std::vector<char> &out, const T &value) {
    const char *p = reinterpret_cast<const char *>(&value);
    out.insert(out.end(), p, p + sizeof value);
}

template <typename T>
void PutArray(std::vector<char> &out, const std::vector<T> &values) {
    Put(out, std::uint64_t(values.size()));
    const char *p = reinterpret_cast<const char *>(values.data());
    out.insert(out.end(), p, p + values.size() * sizeof(T));
}

class Reader {
  public:
    Reader(const char *data, std::size_t size) : at_(data), end_(data + size) {}
    template <typename T>
    bool Get(T &value) {
        if (std::size_t(end_ - at_) < sizeof value) return false;
        std::memcpy(&value, at_, sizeof value);
        at_ += sizeof value;
        return true;
    }
    template <typename T>
    bool GetArray(std::vector<T> &values) {
        std::uint64_t n = 0;
        if (!Get(n) || n > std::uint64_t(end_ - at_) / sizeof(T)) return false;
        values.resize(std::size_t(n));
        std::memcpy(values.data(), at_, std::size_t(n) * sizeof(T));
        at_ += std::size_t(n) * sizeof(T);
        return true;
    }
    bool AtEnd() const { return at_ == end_; }

  private:
    const char *at_, *end_;
};

bool Meets(const BlockRecord &r, const std::vector<int> &rects) {
    for (std::size_t i = 0; i + 3 < rects.size(); i += 4)
        if (r.left < rects[i + 2] && rects[i] <= r.right && r.top < rects[i + 3] && rects[i + 1] <= r.bottom)
            return true;
    return false;
}

}  // namespace

bool Handover::SameGrid(const FrameSetup &setup) const {
    return width == setup.width && height == setup.height && left == setup.left && top == setup.top &&
           right == setup.right && bottom == setup.bottom && blockSize == setup.blockSize &&
           optionsHash == setup.optionsHash;
}

std::size_t WriteHandover(const SampleStore &store, const FrameSetup &setup, const std::vector<int> &rects,
                          std::vector<char> &out) {
    out.insert(out.end(), kMagic, kMagic + sizeof kMagic);
    Put(out, std::uint32_t(sizeof(StoredSample)));
    Put(out, std::uint32_t(sizeof(Segment)));
    Put(out, std::uint32_t(sizeof(FanApexes)));
    Put(out, std::int32_t(setup.frameNumber));
    for (int v : {setup.width, setup.height, setup.left, setup.top, setup.right, setup.bottom, setup.blockSize})
        Put(out, std::int32_t(v));
    Put(out, setup.optionsHash);
    const std::size_t countAt = out.size();
    Put(out, std::uint32_t(0));
    std::uint32_t count = 0;
    for (std::size_t serial = 0; serial < store.BlockCount(); ++serial) {
        const BlockRecord *r = store.Find(serial);
        if (!r || r->opaque || !Meets(*r, rects)) continue;
        Put(out, std::uint32_t(serial));
        for (int v : {r->left, r->top, r->right, r->bottom}) Put(out, std::int32_t(v));
        Put(out, std::uint8_t(r->hasEverything));
        Put(out, std::uint64_t(r->deadSegments));
        PutArray(out, r->samples);
        PutArray(out, r->segments);
        PutArray(out, r->pixels);
        Put(out, r->apexes);
        PutArray(out, r->fanOf);
        ++count;
    }
    std::memcpy(&out[countAt], &count, sizeof count);
    return count;
}

bool ReadHandover(const char *data, std::size_t size, Handover &out, std::string &why) {
    Reader in(data, size);
    char magic[sizeof kMagic];
    std::uint32_t sampleSize = 0, segmentSize = 0, apexesSize = 0, count = 0;
    std::int32_t frame = 0, grid[7];
    if (!in.Get(magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) {
        why = "not a frame-coherence hand-over";
        return false;
    }
    if (!in.Get(sampleSize) || !in.Get(segmentSize) || !in.Get(apexesSize) || sampleSize != sizeof(StoredSample) ||
        segmentSize != sizeof(Segment) || apexesSize != sizeof(FanApexes)) {
        why = "a hand-over from another povray-fc build";
        return false;
    }
    if (!in.Get(frame) || !in.Get(grid) || !in.Get(out.optionsHash) || !in.Get(count)) {
        why = "a hand-over cut short";
        return false;
    }
    out.frame = frame;
    out.width = grid[0];
    out.height = grid[1];
    out.left = grid[2];
    out.top = grid[3];
    out.right = grid[4];
    out.bottom = grid[5];
    out.blockSize = grid[6];
    out.blocks.clear();
    for (std::uint32_t i = 0; i < count; ++i) {
        HandedBlock b;
        b.record = std::make_unique<BlockRecord>();
        BlockRecord &r = *b.record;
        std::int32_t rect[4];
        std::uint8_t everything = 0;
        std::uint64_t dead = 0;
        if (!in.Get(b.serial) || !in.Get(rect) || !in.Get(everything) || !in.Get(dead) || !in.GetArray(r.samples) ||
            !in.GetArray(r.segments) || !in.GetArray(r.pixels) || !in.Get(r.apexes) || !in.GetArray(r.fanOf)) {
            why = "a hand-over cut short";
            return false;
        }
        r.left = rect[0];
        r.top = rect[1];
        r.right = rect[2];
        r.bottom = rect[3];
        r.hasEverything = everything != 0;
        r.deadSegments = std::size_t(dead);
        // What a block record must hold for BlockTracer to read it without going out of
        // bounds: anything else is refused whole.
        const bool shaped = r.right >= r.left && r.bottom >= r.top &&
                            r.pixels.size() == std::size_t(r.Width()) * std::size_t(r.Height()) * 5 &&
                            r.fanOf.size() == r.segments.size() && r.apexes.count >= 0 &&
                            r.apexes.count <= FanApexes::kMax && r.deadSegments <= r.segments.size();
        bool samplesFit = shaped;
        for (std::size_t s = 0; samplesFit && s < r.samples.size(); ++s) {
            const StoredSample &sample = r.samples[s];
            samplesFit = sample.group < r.GroupCount() &&
                         (sample.segmentCount == StoredSample::kEverything ||
                          std::uint64_t(sample.firstSegment) + sample.segmentCount <= r.segments.size());
        }
        if (!samplesFit) {
            why = "a hand-over with a malformed block";
            return false;
        }
        // Clearances are stamped against the sender's frames (change_drift.h): none is
        // trusted here.
        for (StoredSample &sample : r.samples) sample.clearStamp = sample.clearance = 0;
        out.blocks.push_back(std::move(b));
    }
    if (!in.AtEnd()) {
        why = "a hand-over with bytes after its last block";
        return false;
    }
    return true;
}

}  // namespace povrayfc
