// protocol.h - the fc-master / fc-slave PVM messages: their tags and payloads, and one
// pack/unpack pair per message (protocol.cpp).
//
// The table in coordinator/README.md ("Protocol") is the one description of the messages:
// direction, payload and reply of every tag. In short: a job is one frame and a set of
// tiles, rendered by a slave's renderer with one parse; a slave holds at most two jobs and
// gets its next one in reply to a result (self-scheduling).
//
// Frames are POV-Ray frame numbers; rectangles are 0-based, half-open pixel coordinates
// [x0,x1) x [y0,y1) in the full image. Data is packed with PvmDataDefault (XDR), so hosts of
// different byte order interoperate; strings travel as length + bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frame-channel/frame_record.h"     // Rect, and the FrameRecord a result carries

namespace fc {

enum Tag {
    FC_HELLO = 101,
    FC_SETUP = 102,
    FC_JOB = 103,
    FC_FRAME = 104,
    FC_PROGRESS = 105,
    FC_FAIL = 107,
    FC_CANCEL = 110,
    FC_PING = 111,
    FC_QUIT = 112,
    FC_ABANDON = 113,
    FC_TASKEXIT = 120,
    FC_HOSTDEL = 121,
    FC_HOSTADD = 122,
    FC_MASTEREXIT = 123,
};

const char *tag_name(int tag);

struct Hello {
    std::string host;
    int cpus = 1;
    int pid = 0;
};

struct Setup {
    std::string renderer;               // absolute path of POV-Ray on the slave's host
    std::string cwd;                    // the master's directory: relative scene paths work
    std::vector<std::string> options;   // the user's POV-Ray options, unchanged
    std::vector<std::string> extra;     // options the master adds (frame coherence)
    int width = 0, height = 0;
    int digits = 0;                     // digits of frame numbers in output names; 0 = still
    int last_frame = 0;                 // last frame of the animation subset (+EF)
    int coherent = 0;                   // frame coherence is on (renderer.h: tile changes)
    int timeout = 0;                    // master's --timeout: heartbeat every min(2, timeout/4) s,
                                        // idle slave gives up after max(300, 10 x timeout) s
    int nice = 0;                       // nice increment for the renderer
};

struct JobMsg {
    int job = 0;
    int frame = 0;
    std::vector<int> tiles;             // tile numbers, echoed in the result
    std::vector<Rect> rects;            // their rectangles
    int threads = 1;                    // POV-Ray work threads (+WT)
};

// The renderer's record of a frame (frame_record.h: its rectangles, pixels, file, statistics
// and the files its parse read, `reads`: relative paths there are the renderer's directory's,
// the master's), with the job it answers.
struct FrameResult : FrameRecord {
    int job = 0;
    std::vector<int> tiles;             // the job's tiles, one per rectangle
    int fresh = 0;                      // the renderer's first frame (fc traced everything)
};

struct Progress {
    int job = 0;
    int frame = 0;
};

struct Failure {
    int job = 0;
    int frame = 0;
    int scene_error = 0;                // 1: POV-Ray rejected the scene (fatal)
    int status = 0;                     // wait status of POV-Ray, or -1 for a slave-side error
    int abandoned = 0;                  // 1: the master abandoned the job (FC_ABANDON)
    std::string message;                // POV-Ray's error lines (file, line, message), or its
                                        // last console lines for an abandoned job
};

// Each message has one pack function (initsend + pack, returns the pvm status of the last
// pack call, < 0 on error) and one unpack function (unpacks the active receive buffer,
// returns false on a malformed message).
int pack(const Hello &m);
bool unpack(Hello &m);
int pack(const Setup &m);
bool unpack(Setup &m);
int pack(const JobMsg &m);
bool unpack(JobMsg &m);
int pack(const FrameResult &m);
bool unpack(FrameResult &m);
int pack(const Progress &m);
bool unpack(Progress &m);
int pack(const Failure &m);
bool unpack(Failure &m);
int pack_int(int v);        // FC_CANCEL, FC_ABANDON
bool unpack_int(int &v);
int pack_empty();           // FC_PING, FC_QUIT

// Send the packed active send buffer; returns the pvm status (< 0 on error).
int send_packed(int tid, int tag);

// Pack m and send it; returns the pvm status (< 0 on error).
template <class M> int send_msg(int tid, int tag, const M &m)
{
    int r = pack(m);
    return r < 0 ? r : send_packed(tid, tag);
}

} // namespace fc
