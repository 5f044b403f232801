// BlockCosts: the processor time the render threads spent on each block of a frame, so a
// renderer that holds some tiles of a frame can say what each of them cost. fc-master
// balances its slaves by these costs: with frame coherence a tile's cost depends on what
// moves in and near it (a tile of sky costs almost nothing, one with a moving marble
// hundreds of times more), not on its pixels.
#ifndef POVRAYFC_BLOCK_COSTS_H
#define POVRAYFC_BLOCK_COSTS_H

#include <mutex>
#include <vector>

namespace povrayfc {

// A block ([left..right] x [top..bottom], inclusive) and the processor seconds its
// render thread spent on it.
struct BlockCost {
    int left = 0, top = 0, right = -1, bottom = -1;
    double seconds = 0.0;
};

// The costs of one frame's blocks; the render threads add to it concurrently.
class BlockCosts {
  public:
    void Add(const BlockCost &cost);
    void Clear();
    void Assign(std::vector<BlockCost> costs);
    std::vector<BlockCost> Snapshot() const;

  private:
    mutable std::mutex mutex_;
    std::vector<BlockCost> costs_;
};

// Processor time of the calling thread, in seconds: what a block cost its thread, free of
// the time the thread waited for the processor (another process, a CPU quota).
double ThreadCpuSeconds();

// The seconds of `costs` per rectangle of `rects` (each {left, top, right, bottom},
// inclusive, disjoint): a block's seconds are shared among the rectangles it meets by
// the pixels it has in each (a block that meets none counts nowhere).
std::vector<double> CostsPerRect(const std::vector<BlockCost> &costs, const std::vector<BlockCost> &rects);

}  // namespace povrayfc

#endif
