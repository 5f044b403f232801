// BlockCosts: per-block processor time of a frame, and its share per rectangle.
#include "povrayfc/block_costs.h"

#include <algorithm>
#include <ctime>

namespace povrayfc {

void BlockCosts::Add(const BlockCost &cost) {
    std::lock_guard<std::mutex> lock(mutex_);
    costs_.push_back(cost);
}

void BlockCosts::Clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    costs_.clear();
}

void BlockCosts::Assign(std::vector<BlockCost> costs) {
    std::lock_guard<std::mutex> lock(mutex_);
    costs_ = std::move(costs);
}

std::vector<BlockCost> BlockCosts::Snapshot() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return costs_;
}

double ThreadCpuSeconds() {
    timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

namespace {

long Overlap(const BlockCost &a, const BlockCost &b) {
    const long w = long(std::min(a.right, b.right)) - long(std::max(a.left, b.left)) + 1;
    const long h = long(std::min(a.bottom, b.bottom)) - long(std::max(a.top, b.top)) + 1;
    return w > 0 && h > 0 ? w * h : 0;
}

}  // namespace

std::vector<double> CostsPerRect(const std::vector<BlockCost> &costs, const std::vector<BlockCost> &rects) {
    std::vector<double> result(rects.size(), 0.0);
    std::vector<long> inside(rects.size());
    for (const BlockCost &block : costs) {
        long total = 0;
        for (std::size_t r = 0; r < rects.size(); ++r) total += inside[r] = Overlap(block, rects[r]);
        if (total == 0) continue;
        for (std::size_t r = 0; r < rects.size(); ++r)
            result[r] += block.seconds * double(inside[r]) / double(total);
    }
    return result;
}

}  // namespace povrayfc
