// protocol.cpp - pack/unpack pairs for every fc message (see the table in protocol.h).
#include "protocol.h"

#include <pvm3.h>

#include "text.h"
#include "watchdog.h"

namespace fc {

const char *tag_name(int tag)
{
    switch (tag) {
    case FC_HELLO: return "FC_HELLO";
    case FC_SETUP: return "FC_SETUP";
    case FC_JOB: return "FC_JOB";
    case FC_FRAME: return "FC_FRAME";
    case FC_PROGRESS: return "FC_PROGRESS";
    case FC_FAIL: return "FC_FAIL";
    case FC_CANCEL: return "FC_CANCEL";
    case FC_PING: return "FC_PING";
    case FC_QUIT: return "FC_QUIT";
    case FC_ABANDON: return "FC_ABANDON";
    case FC_TASKEXIT: return "FC_TASKEXIT";
    case FC_HOSTDEL: return "FC_HOSTDEL";
    case FC_HOSTADD: return "FC_HOSTADD";
    case FC_MASTEREXIT: return "FC_MASTEREXIT";
    default: return "unknown tag";
    }
}

namespace {

// Packing helpers keep the first error: a pack chain reads as a list of fields.
struct Packer {
    int status = 0;
    Packer() { status = pvm_initsend(PvmDataDefault); if (status > 0) status = 0; }
    Packer &i(int v) { if (status >= 0) status = pvm_pkint(&v, 1, 1); return *this; }
    Packer &d(double v) { if (status >= 0) status = pvm_pkdouble(&v, 1, 1); return *this; }
    Packer &s(const std::string &v)
    {
        i(int(v.size()));
        if (status >= 0 && !v.empty())
            status = pvm_pkbyte(const_cast<char *>(v.data()), int(v.size()), 1);
        return *this;
    }
    Packer &r(const Rect &v) { return i(v.x0).i(v.y0).i(v.x1).i(v.y1); }
    Packer &strings(const std::vector<std::string> &v)
    {
        i(int(v.size()));
        for (const std::string &x : v)
            s(x);
        return *this;
    }
    Packer &ints(const std::vector<int> &v)
    {
        i(int(v.size()));
        if (status >= 0 && !v.empty())
            status = pvm_pkint(const_cast<int *>(v.data()), int(v.size()), 1);
        return *this;
    }
    Packer &rects(const std::vector<Rect> &v)
    {
        i(int(v.size()));
        for (const Rect &x : v)
            r(x);
        return *this;
    }
    Packer &bytes(const std::vector<uint8_t> &v)
    {
        i(int(v.size()));
        if (status >= 0 && !v.empty())
            status = pvm_pkbyte(reinterpret_cast<char *>(const_cast<uint8_t *>(v.data())),
                                int(v.size()), 1);
        return *this;
    }
};

struct Unpacker {
    bool ok = true;
    Unpacker &i(int &v) { if (ok) ok = pvm_upkint(&v, 1, 1) >= 0; return *this; }
    Unpacker &d(double &v) { if (ok) ok = pvm_upkdouble(&v, 1, 1) >= 0; return *this; }
    Unpacker &s(std::string &v)
    {
        int n = 0;
        i(n);
        if (ok && (n < 0 || n > (64 << 20)))
            ok = false;
        if (ok) {
            v.assign(size_t(n), '\0');
            if (n > 0)
                ok = pvm_upkbyte(&v[0], n, 1) >= 0;
        }
        return *this;
    }
    Unpacker &r(Rect &v) { return i(v.x0).i(v.y0).i(v.x1).i(v.y1); }
    Unpacker &strings(std::vector<std::string> &v)
    {
        int n = 0;
        i(n);
        if (ok && (n < 0 || n > 100000))
            ok = false;
        v.clear();
        for (int k = 0; ok && k < n; k++) {
            std::string x;
            s(x);
            v.push_back(x);
        }
        return *this;
    }
    Unpacker &ints(std::vector<int> &v)
    {
        int n = 0;
        i(n);
        if (ok && (n < 0 || n > (1 << 24)))
            ok = false;
        if (ok) {
            v.resize(size_t(n));
            if (n > 0)
                ok = pvm_upkint(v.data(), n, 1) >= 0;
        }
        return *this;
    }
    Unpacker &rects(std::vector<Rect> &v)
    {
        int n = 0;
        i(n);
        if (ok && (n < 0 || n > (1 << 24)))
            ok = false;
        v.clear();
        for (int k = 0; ok && k < n; k++) {
            Rect x;
            r(x);
            v.push_back(x);
        }
        return *this;
    }
    Unpacker &bytes(std::vector<uint8_t> &v)
    {
        int n = 0;
        i(n);
        if (ok && (n < 0 || n > (1 << 30)))
            ok = false;
        if (ok) {
            v.resize(size_t(n));
            if (n > 0)
                ok = pvm_upkbyte(reinterpret_cast<char *>(v.data()), n, 1) >= 0;
        }
        return *this;
    }
};

} // namespace

int send_packed(int tid, int tag)
{
    // A send blocks only while the peer's socket is full and the peer reads nothing (a
    // stopped slave with a large message in front of it).
    watchdog::Guard guard(strf("sending %s to t%x", tag_name(tag), unsigned(tid)), 30,
                          strf("task t%x does not take messages (stopped?)", unsigned(tid)));
    return pvm_send(tid, tag);
}

int pack(const Hello &m) { return Packer().s(m.host).i(m.cpus).i(m.pid).status; }
bool unpack(Hello &m) { return Unpacker().s(m.host).i(m.cpus).i(m.pid).ok; }

int pack(const Setup &m)
{
    return Packer()
        .s(m.renderer).s(m.cwd).strings(m.options).strings(m.extra)
        .i(m.width).i(m.height).i(m.digits).i(m.last_frame).i(m.coherent).i(m.timeout).i(m.nice)
        .status;
}
bool unpack(Setup &m)
{
    return Unpacker()
        .s(m.renderer).s(m.cwd).strings(m.options).strings(m.extra)
        .i(m.width).i(m.height).i(m.digits).i(m.last_frame).i(m.coherent).i(m.timeout).i(m.nice)
        .ok;
}

int pack(const JobMsg &m)
{
    return Packer().i(m.job).i(m.frame).ints(m.tiles).rects(m.rects).i(m.threads).status;
}
bool unpack(JobMsg &m)
{
    bool ok = Unpacker().i(m.job).i(m.frame).ints(m.tiles).rects(m.rects).i(m.threads).ok;
    return ok && !m.rects.empty() && m.tiles.size() == m.rects.size();
}

int pack(const FrameResult &m)
{
    return Packer()
        .i(m.job).i(m.frame).ints(m.tiles).rects(m.rects).d(m.rays).d(m.parse_seconds)
        .d(m.trace_seconds).i(m.fresh).s(m.encoding).bytes(m.data).bytes(m.file)
        .d(m.file_gamma).s(m.reads).status;
}
bool unpack(FrameResult &m)
{
    bool ok = Unpacker()
        .i(m.job).i(m.frame).ints(m.tiles).rects(m.rects).d(m.rays).d(m.parse_seconds)
        .d(m.trace_seconds).i(m.fresh).s(m.encoding).bytes(m.data).bytes(m.file)
        .d(m.file_gamma).s(m.reads).ok;
    return ok && !m.rects.empty() && m.tiles.size() == m.rects.size();
}

int pack(const Progress &m) { return Packer().i(m.job).i(m.frame).status; }
bool unpack(Progress &m) { return Unpacker().i(m.job).i(m.frame).ok; }

int pack(const Failure &m)
{
    return Packer().i(m.job).i(m.frame).i(m.scene_error).i(m.status).i(m.abandoned).s(m.message)
        .status;
}
bool unpack(Failure &m)
{
    return Unpacker().i(m.job).i(m.frame).i(m.scene_error).i(m.status).i(m.abandoned).s(m.message)
        .ok;
}

int pack_int(int v) { return Packer().i(v).status; }
bool unpack_int(int &v) { return Unpacker().i(v).ok; }

int pack_empty() { return Packer().status; }

} // namespace fc
