// liveness.cpp - deadlines learned from the run (see liveness.h).
#include "liveness.h"

#include <algorithm>
#include <vector>

namespace fc {

namespace {

double median(const std::deque<double> &values)
{
    if (values.empty())
        return 0;
    // The mean of the two middle values of an even count: early in a run (two jobs, one of
    // them a renderer's first) the larger alone would stretch every deadline.
    std::vector<double> v(values.begin(), values.end());
    std::sort(v.begin(), v.end());
    size_t mid = v.size() / 2;
    return v.size() % 2 ? v[mid] : (v[mid - 1] + v[mid]) / 2;
}

void remember(std::deque<double> &values, double v, size_t keep)
{
    values.push_back(v);
    if (values.size() > keep)
        values.pop_front();
}

} // namespace

void Liveness::job_took(int slave, int host, double pixels, double seconds)
{
    delivered_.insert(slave);
    if (pixels <= 0 || seconds <= 0)
        return;
    remember(per_host_[host], seconds / pixels, kHistory);
    remember(all_, seconds / pixels, kHistory);
}

double Liveness::seconds_per_pixel(int host) const
{
    auto it = per_host_.find(host);
    if (it != per_host_.end() && !it->second.empty())
        return median(it->second);
    return median(all_);
}

double Liveness::deadline(int slave, int host, double pixels, bool copy, double fresh_cost) const
{
    double per_pixel = seconds_per_pixel(host);
    if (per_pixel <= 0)
        return std::max(kFloor, fallback_);
    double expected = per_pixel * pixels;
    if (copy || !delivered_.count(slave))
        expected *= std::max(1.0, fresh_cost);
    return std::max(kFloor, kFactor * expected);
}

double Liveness::hang_deadline(int host, double pixels) const
{
    double per_pixel = seconds_per_pixel(host);
    if (per_pixel <= 0)
        return std::max(kHangFloor, fallback_);
    return std::max(kHangFloor, kHangFactor * per_pixel * pixels);
}

} // namespace fc
