// cost_model.cpp - what rendering costs, from the results (see cost_model.h).
#include "cost_model.h"

#include <algorithm>

namespace fc {

double CostModel::speed(int slave) const
{
    auto it = speed_.find(slave);
    return it == speed_.end() ? 0 : it->second;
}

void CostModel::note_speed(int slave, double pixels, double seconds)
{
    if (seconds <= 0 || pixels <= 0)
        return;
    job_seconds_ = job_seconds_ <= 0 ? seconds
                                     : (1 - kSpeedWeight) * job_seconds_ + kSpeedWeight * seconds;
    double v = pixels / seconds;
    auto it = speed_.find(slave);
    speed_[slave] = it == speed_.end() ? v : (1 - kSpeedWeight) * it->second + kSpeedWeight * v;
}

void CostModel::note_result(const ResultCost &r)
{
    double seconds = r.parse + r.trace;
    // With fc, a renderer's frame after one it did not render before it (a jump to another
    // range) is coherent with an older frame: neither fresh nor a measure of coherent speed.
    auto last = last_index_.find(r.slave);
    bool jump = fc_ && !r.fresh && last != last_index_.end() && r.index != last->second + 1;
    last_index_[r.slave] = r.index;
    if (fc_) {
        // What fc saved: its first frame in a renderer is traced in full, the yardstick.
        rays_spent_ += std::max(0.0, r.rays);
        seconds_spent_ += r.trace;
        pixels_traced_ += r.pixels;
        if (r.fresh) {
            fresh_rays_ += std::max(0.0, r.rays);
            fresh_seconds_ += r.trace;
            fresh_pixels_ += r.pixels;
        }
        if (jump) {
            jump_seconds_ += r.trace;
            jump_pixels_ += r.pixels;
        }
    }
    // A fresh renderer with frame coherence traced and recorded everything: no measure of
    // the slave's speed on coherent frames.
    if (!(r.fresh && fc_) && !jump)
        note_speed(r.slave, r.pixels, seconds);
    double coherent_pixels = pixels_traced_ - fresh_pixels_ - jump_pixels_;
    double coherent_seconds = seconds_spent_ - fresh_seconds_ - jump_seconds_;
    if (coherent_pixels > 0 && coherent_seconds > 0) {
        double coherent = coherent_seconds / coherent_pixels;
        if (fresh_pixels_ > 0)
            fresh_cost_ = (fresh_seconds_ / fresh_pixels_) / coherent;
        if (jump_pixels_ > 0)
            jump_cost_ = (jump_seconds_ / jump_pixels_) / coherent;
    }
}

Savings CostModel::savings() const
{
    Savings s;
    s.rays_spent = rays_spent_;
    s.seconds_spent = seconds_spent_;
    if (fresh_pixels_ > 0 && pixels_traced_ > fresh_pixels_) {
        s.known = true;
        s.rays_full = fresh_rays_ / fresh_pixels_ * pixels_traced_;
        s.seconds_full = fresh_seconds_ / fresh_pixels_ * pixels_traced_;
    }
    return s;
}

} // namespace fc
