// frame_book.h - every frame of the run, in one place: which of its cells are done, its pixels
// while it is assembled, the order in which complete frames are written, and the writing.
//
// A frame to render lives in memory (its stored samples: zeros outside the render area like
// POV-Ray's own partial renders) from its first tile to its last; then it is complete and
// waits its turn: complete frames are written in frame order, encoded (frame_encoder.h: a
// frame that came whole with the file POV-Ray's writer made of it is that file) and stored
// (frame_files.h), and its memory is freed. So the master holds only the frames in flight.
// Frames dithered by error diffusion come as unquantized values and are dithered when written,
// once, over the whole frame, by POV-Ray's own dither handler in fc-image-writer
// (image_writer_client.h).
//
// A frame that needs no rendering (already complete on disk, skipped by a Pre_Frame_Command,
// given up after failing) has its cells marked done too: the schedule (schedule.h) reads the
// cells and hands out only what is missing.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cell_grid.h"
#include "frame_encoder.h"
#include "frame_files.h"
#include "frame-channel/frame_record.h"
#include "protocol.h"

namespace fc {

class FrameBook {
public:
    enum class State { ToRender, Resumed, Assembling, Complete, Written, Skipped, GivenUp };

    // Complete frames kept in memory while OpenImageIO loads; with more, writing waits for the
    // load. 32 slaves on 2 cores once slowed the load to 5 s, while all 24 frames completed.
    static const size_t kFramesWhileLoading = 8;

    FrameBook(FrameFiles &files, FrameEncoder &encoder, int width, int height,
              const std::vector<int> &frames, int tiles);

    const CellGrid &cells() const { return cells_; }
    FrameFiles &files() { return files_; }

    int count() const { return int(frames_.size()); }
    // POV-Ray's number of frame index i, and the index of a frame number (-1: not this run's).
    int number(int index) const { return frames_[size_t(index)]; }
    int index_of(int number) const;
    State state(int index) const { return state_[size_t(index)]; }

    // Before the render: frame index i is on disk, complete and correct.
    void resumed(int index);

    // The first job of frame index i goes out: true the first time (its Pre_Frame_Command
    // runs then).
    bool start(int index);
    // When it went out (seconds of the wall clock; 0: not yet): files changed after that may
    // not be what its parse read.
    double started_at(int index) const { return started_at_[size_t(index)]; }

    // The files frame index i depends on (frame_inputs.h), recorded with it when written.
    bool has_inputs(int index) const { return inputs_.count(index) != 0; }
    void set_inputs(int index, const FrameInputs &inputs) { inputs_[index] = inputs; }
    // A Pre_Frame_Command skipped frame index i: it gets no file.
    void skip(int index);

    // What went wrong with a frame while it was rendered: failures (not the scene's) and
    // stalls (liveness.h), the hosts they happened on, and POV-Ray's last words.
    struct Trouble {
        int failures = 0, stalls = 0;
        double first_stall = -1;  // when a job of the frame first stalled (-1: never)
        std::set<std::string> hosts;
        std::string last_words;
    };
    Trouble &trouble(int index) { return trouble_[index]; }
    // When a job of frame index first stalled, or -1 (no entry made).
    double first_stall(int index) const {
        auto it = trouble_.find(index);
        return it == trouble_.end() ? -1 : it->second.first_stall;
    }

    // Frame index i is given up (it failed or hung on the hosts that tried it, or the scene
    // fails there and --keep-going goes on): no file; why says so.
    void give_up(int index, const std::string &why);
    // The frames given up, in frame order, with why.
    std::vector<std::pair<int, std::string>> given_up() const;

    // A result of frame index i: its tiles not done before are marked and their pixels stored
    // (appended to fresh); the frame is complete when its last cell arrives. False with err
    // on a malformed payload or an encoding that does not carry the output format.
    bool deliver(int index, FrameResult &result, std::vector<int> &fresh, std::string &err);

    // The complete frame to write next (the lowest index), or -1: none, or (unless wait) it
    // stays in memory while OpenImageIO still loads and would encode it, as long as no more
    // than kFramesWhileLoading wait, so that no slave waits for its next job meanwhile.
    int next_to_write(bool wait) const;
    // Write frame index i (complete) and free its memory; its samples move to `samples` (for
    // the preview). False with err; then disk_full tells whether the disk ran out of space.
    bool write(int index, std::vector<uint8_t> &samples, bool &disk_full, std::string &err);

    // Every frame has all its cells: nothing more to render.
    bool all_rendered() const { return cells_.all_done(); }
    int resumed_count() const { return resumed_; }
    int written_count() const { return written_; }
    int skipped_count() const { return skipped_; }
    int given_up_count() const { return given_up_; }
    // Frames held in memory.
    size_t held() const { return pixels_.size(); }

private:
    struct Pixels {
        std::vector<uint8_t> samples;           // width * height * 3 stored samples
        std::vector<float> values;              // diffusion dithering: unquantized, or empty
        Diffusion diffusion;                    // and how to dither them
        std::vector<uint8_t> file;              // POV-Ray's file of the whole frame, or empty
        double file_gamma = 0;                  // the gamma its file records (0: not said)
    };

    bool put(int index, FrameResult &r, const std::vector<char> &keep, std::string &err);
    void no_more_work(int index, State state);

    FrameFiles &files_;
    FrameEncoder &encoder_;
    int width_, height_;
    std::vector<int> frames_;
    std::map<int, int> index_of_;
    CellGrid cells_;
    std::vector<State> state_;
    std::vector<char> started_;
    std::vector<double> started_at_;
    std::map<int, FrameInputs> inputs_;         // frames in flight
    std::map<int, Pixels> pixels_;              // frames being assembled or complete
    std::set<int> complete_;                    // complete, not written yet
    std::map<int, Trouble> trouble_;
    std::map<int, std::string> given_up_why_;
    int resumed_ = 0, written_ = 0, skipped_ = 0, given_up_ = 0;
};

} // namespace fc
