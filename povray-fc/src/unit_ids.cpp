// UnitIds: see povrayfc/unit_ids.h.
#include "povrayfc/unit_ids.h"

namespace povrayfc {

void UnitIds::Reset(std::size_t unitCount) {
    current_.resize(unitCount);
    for (std::size_t i = 0; i < unitCount; ++i) current_[i] = std::uint32_t(i);
    limit_ = std::uint32_t(unitCount);
    previous_.clear();
    free_.clear();
    released_.clear();
}

std::uint32_t UnitIds::Take() {
    if (!free_.empty()) {
        const std::uint32_t id = free_.back();
        free_.pop_back();
        return id;
    }
    return limit_++;
}

void UnitIds::Advance(const std::vector<std::uint32_t> &continues, const std::vector<std::uint32_t> &vanished,
                      std::vector<std::uint32_t> &changedIds) {
    // Ids given up last frame are referred to by no sample any more.
    free_.insert(free_.end(), released_.begin(), released_.end());
    released_.clear();
    std::vector<std::uint32_t> next(continues.size(), kNone);
    std::vector<std::uint8_t> continued(current_.size(), 0);
    for (std::size_t i = 0; i < continues.size(); ++i)
        if (continues[i] != kNone && continues[i] < current_.size() && !continued[continues[i]]) {
            next[i] = current_[continues[i]];
            continued[continues[i]] = 1;
        }
    for (std::uint32_t last : vanished) {
        if (last >= current_.size()) continue;
        changedIds.push_back(current_[last]);
        if (!continued[last]) released_.push_back(current_[last]);
    }
    for (std::uint32_t &id : next)
        if (id == kNone) id = Take();
    previous_.swap(current_);
    current_.swap(next);
}

}  // namespace povrayfc
