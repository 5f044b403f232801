// cost_model.h - what rendering costs, measured from the results of the run: each slave's
// speed, how long a job takes, what a renderer's fresh start and a jump to another range cost
// in coherent frames, and what frame coherence saved.
//
// Fed in one place, once per result (note_result); read by the schedule (schedule.h: how to
// divide, split and duplicate work) and by the statistics (what fc saved).
//
// With frame coherence a renderer traces its first frame in full (fresh), and a renderer that
// jumps forward to another range is coherent with an older frame: neither measures a slave's
// speed on coherent frames, and each is priced against that speed (fresh_cost, jump_cost).
// Without fc no renderer keeps state in its tiles: moving a tile to another slave costs
// nothing extra (cheap_moves).
#pragma once

#include <map>

namespace fc {

// One result's cost, as the master sees it.
struct ResultCost {
    int slave = 0;
    int index = 0;              // frame index
    double pixels = 0;          // of its rectangles
    double parse = 0, trace = 0;    // the renderer's seconds
    double rays = 0;            // < 0: not reported
    bool fresh = false;         // the renderer's first frame
};

// What frame coherence saved, estimated from the renderers' first frames (which fc traces in
// full): rays and trace seconds per pixel there, times every pixel rendered, against what was
// spent. The rays are those a render without fc traces (fc is exact); the seconds are an upper
// bound, since a first frame also records every ray.
struct Savings {
    bool known = false;
    double rays_spent = 0, rays_full = 0;
    double seconds_spent = 0, seconds_full = 0;
};

class CostModel {
public:
    static constexpr double kSpeedWeight = 0.3;     // weight of the newest measurement

    // Frame coherence on: fresh starts and jumps are priced, and a moved tile costs a trace.
    void set_frame_coherence(bool fc) { fc_ = fc; cheap_moves_ = !fc; }

    // A result arrived.
    void note_result(const ResultCost &r);

    // What the schedule reads.
    bool cheap_moves() const { return cheap_moves_; }
    // A slave's measured speed, pixels a second (smoothed), or 0 when not measured yet.
    double speed(int slave) const;
    // How long a job takes, seconds (smoothed; 0 before the first).
    double job_seconds() const { return job_seconds_; }
    // A fresh renderer's first frame, in coherent frames (1 until measured).
    double fresh_cost() const { return fresh_cost_; }
    // A renderer's first frame after a forward jump, in coherent frames (0: not measured).
    double jump_cost() const { return jump_cost_; }

    // What fc saved so far.
    Savings savings() const;

    // The measurements themselves, as note_result makes them (for tests and simulations).
    void note_speed(int slave, double pixels, double seconds);
    void set_cheap_moves(bool cheap) { cheap_moves_ = cheap; }
    void set_fresh_cost(double frames) { fresh_cost_ = frames; }
    void set_jump_cost(double frames) { jump_cost_ = frames; }

private:
    bool fc_ = false;
    bool cheap_moves_ = false;
    std::map<int, double> speed_;       // pixels per second, smoothed
    double job_seconds_ = 0;
    double fresh_cost_ = 1;
    double jump_cost_ = 0;
    std::map<int, int> last_index_;     // each slave's last frame index
    // Sums over the results: all traced, the fresh ones, the ones after a jump.
    double rays_spent_ = 0, seconds_spent_ = 0, pixels_traced_ = 0;
    double fresh_rays_ = 0, fresh_seconds_ = 0, fresh_pixels_ = 0;
    double jump_seconds_ = 0, jump_pixels_ = 0;
};

} // namespace fc
