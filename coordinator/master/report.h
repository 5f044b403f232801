// report.h - what fc-master tells the user on stderr: progress while rendering and a summary at
// the end (the --stats JSON file is run_stats.h's).
//
// Progress counts only the work of this run (frames already in the output directory are
// neither done work nor part of the ETA), and never says 100% before the last frame is
// written. On a terminal (stderr) it is a block of lines redrawn in place, each cut to the
// terminal's width (COLUMNS, else TIOCGWINSZ, else 80): a bar with frames and ETA, the frames
// in flight, then one line per host with its throughput. Otherwise a plain line every
// --progress seconds.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "run_stats.h"

namespace fc {

// One host's line of the progress display.
struct HostProgress {
    std::string name;
    int slaves = 0, busy = 0;           // live slaves, and those with work
    double pixels = 0;                  // pixels delivered this run
};

// One progress display.
struct ProgressState {
    double elapsed = 0, eta = -1;
    int frames_done = 0, frames_todo = 0, resumed = 0;
    double fraction = 0;                // of this run's work
    std::vector<int> in_flight;         // frames being rendered
    int busy = 0, slaves = 0;
    double frame_pixels = 1;            // pixels of one frame's render area
    std::vector<HostProgress> hosts;    // the live ones
};

class Report {
public:
    // The end summary fits a terminal of this many columns (lines are shorter).
    static const int kSummaryColumns = 80;

    // interval: seconds between plain progress lines (stderr not a terminal).
    Report(double interval, bool quiet);

    // Called often; prints when due.
    void progress(const ProgressState &p);
    // Erase the live display before other output.
    void clear_line();

    static std::string duration(double seconds);

    // Columns of the terminal on stderr: COLUMNS, else TIOCGWINSZ, else 80.
    static int terminal_columns();

    // The lines of the live display for a terminal of `columns` (each shorter than that).
    static std::vector<std::string> display(const ProgressState &p, int columns, int rows);
    // The plain progress line.
    static std::string plain_line(const ProgressState &p);

    std::string summary(const RunSummary &s) const;

private:
    bool tty_;
    bool quiet_;
    double interval_;
    double last_ = -1e9;
    int lines_open_ = 0;        // lines of the live display on the screen
};

} // namespace fc
