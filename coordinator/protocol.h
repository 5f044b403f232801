// protocol.h - the fc-master / fc-slave PVM message protocol: every tag, its payload, its reply.
//
// The master has one receive point and switches on the tag; a slave holds one work unit at a
// time and gets its next one in reply to FC_DONE (self-scheduling). A work unit is one POV-Ray
// process: one rectangle of the image (a tile, or the whole frame) over a consecutive range of
// frames, so frame coherence can carry state from frame to frame inside it.
//
//  Tag            Direction   Payload                                         Reply
//  -------------  ----------  ----------------------------------------------  ---------------------
//  FC_HELLO       slave->m    Hello: host, cpus, pid                           FC_SETUP
//  FC_SETUP       m->slave    Setup: renderer, cwd, POV-Ray options, W, H,     none (slave idles
//                             frame digits, timeout, nice                      until FC_JOB)
//  FC_JOB         m->slave    Job: unit, rectangle, first/last/step frame,     FC_FRAME per frame,
//                             threads                                          then FC_DONE or FC_FAIL
//  FC_FRAME       slave->m    FrameResult: unit, frame, rectangle, rays,       none
//                             seconds, AA method, 8-bit RGB pixels (top row
//                             first, left to right)
//  FC_PROGRESS    slave->m    Progress: unit, frame, pixels done/total         none (heartbeat, every
//                                                                             ~2 s while rendering)
//  FC_DONE        slave->m    UnitDone: unit, status, frames sent, rays, secs  FC_JOB, or none (idle)
//  FC_FAIL        slave->m    Failure: unit, frame, wait status, message       FC_QUIT (render aborts)
//  FC_TRUNCATE    m->slave    Truncate: unit, requested last frame             FC_TRUNCATED
//  FC_TRUNCATED   slave->m    Truncate: unit, accepted last frame (>= the      none; the master gives
//                             requested one; -1 = unit no longer running)      the tail to an idle slave
//  FC_CANCEL      m->slave    int unit (duplicate finished elsewhere)          FC_DONE, status cancelled
//  FC_PING        m->slave    empty (keeps an idle slave's wait alive)         none
//  FC_QUIT        m->slave    empty                                           none; slave exits
//  FC_TASKEXIT    pvmd->m     int tid          (pvm_notify PvmTaskExit)        -
//  FC_HOSTDEL     pvmd->m     int pvmd tid     (pvm_notify PvmHostDelete)      -
//  FC_HOSTADD     pvmd->m     int n, int tids[n] (pvm_notify PvmHostAdd)       -
//  FC_MASTEREXIT  pvmd->slave int tid          (pvm_notify PvmTaskExit)        - (slave exits)
//
// Frames are POV-Ray frame numbers; rectangles are 0-based, half-open pixel coordinates
// [x0,x1) x [y0,y1) in the full image. Data is packed with PvmDataDefault (XDR), so hosts of
// different byte order interoperate; strings travel as length + bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fc {

enum Tag {
    FC_HELLO = 101,
    FC_SETUP = 102,
    FC_JOB = 103,
    FC_FRAME = 104,
    FC_PROGRESS = 105,
    FC_DONE = 106,
    FC_FAIL = 107,
    FC_TRUNCATE = 108,
    FC_TRUNCATED = 109,
    FC_CANCEL = 110,
    FC_PING = 111,
    FC_QUIT = 112,
    FC_TASKEXIT = 120,
    FC_HOSTDEL = 121,
    FC_HOSTADD = 122,
    FC_MASTEREXIT = 123,
};

const char *tag_name(int tag);

struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    long area() const { return long(width()) * height(); }
    bool operator==(const Rect &o) const
    {
        return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
    }
};

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
    int timeout = 0;                    // master's --timeout: heartbeat every min(2, timeout/4) s,
                                        // idle slave gives up after max(300, 10 x timeout) s
    int nice = 0;                       // nice increment for the renderer
};

struct Job {
    int unit = 0;
    Rect rect;
    int first = 0, last = 0, step = 1;  // frames first, first+step, ... <= last
    int threads = 1;                    // POV-Ray work threads (+WT)
};

struct FrameResult {
    int unit = 0;
    int frame = 0;
    Rect rect;
    double rays = 0;                    // from POV-Ray's statistics
    double seconds = 0;                 // parse + trace wall time of this frame
    int aa_method = 0;                  // 0 = no antialiasing, else POV-Ray's +AM
    std::vector<uint8_t> pixels;        // rect.width() * rect.height() * 3
};

struct Progress {
    int unit = 0;
    int frame = 0;
    int done = 0, total = 0;            // pixels of the current frame
};

enum UnitStatus { UNIT_FINISHED = 0, UNIT_TRUNCATED = 1, UNIT_CANCELLED = 2 };

struct UnitDone {
    int unit = 0;
    int status = UNIT_FINISHED;
    int frames = 0;                     // FC_FRAME messages sent for this unit
    double rays = 0;
    double seconds = 0;                 // wall time of the POV-Ray process
};

struct Failure {
    int unit = 0;
    int frame = 0;
    int status = 0;                     // wait status of POV-Ray, or -1 for a slave-side error
    std::string message;                // POV-Ray's error lines (file, line, message)
};

struct Truncate {
    int unit = 0;
    int last = 0;
};

// Each message has one pack function (initsend + pack, returns the pvm status of the last
// pack call, < 0 on error) and one unpack function (unpacks the active receive buffer,
// returns false on a malformed message).
int pack(const Hello &m);
bool unpack(Hello &m);
int pack(const Setup &m);
bool unpack(Setup &m);
int pack(const Job &m);
bool unpack(Job &m);
int pack(const FrameResult &m);
bool unpack(FrameResult &m);
int pack(const Progress &m);
bool unpack(Progress &m);
int pack(const UnitDone &m);
bool unpack(UnitDone &m);
int pack(const Failure &m);
bool unpack(Failure &m);
int pack(const Truncate &m);
bool unpack(Truncate &m);
int pack_int(int v);        // FC_CANCEL
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
