// protocol.cpp - pack/unpack pairs for every fc message (see the table in protocol.h).
#include "protocol.h"

#include <pvm3.h>

namespace fc {

const char *tag_name(int tag)
{
    switch (tag) {
    case FC_HELLO: return "FC_HELLO";
    case FC_SETUP: return "FC_SETUP";
    case FC_JOB: return "FC_JOB";
    case FC_FRAME: return "FC_FRAME";
    case FC_PROGRESS: return "FC_PROGRESS";
    case FC_DONE: return "FC_DONE";
    case FC_FAIL: return "FC_FAIL";
    case FC_TRUNCATE: return "FC_TRUNCATE";
    case FC_TRUNCATED: return "FC_TRUNCATED";
    case FC_CANCEL: return "FC_CANCEL";
    case FC_PING: return "FC_PING";
    case FC_QUIT: return "FC_QUIT";
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

int send_packed(int tid, int tag) { return pvm_send(tid, tag); }

int pack(const Hello &m) { return Packer().s(m.host).i(m.cpus).i(m.pid).status; }
bool unpack(Hello &m) { return Unpacker().s(m.host).i(m.cpus).i(m.pid).ok; }

int pack(const Setup &m)
{
    return Packer()
        .s(m.renderer).s(m.cwd).strings(m.options).strings(m.extra)
        .i(m.width).i(m.height).i(m.digits).i(m.timeout).i(m.nice)
        .status;
}
bool unpack(Setup &m)
{
    return Unpacker()
        .s(m.renderer).s(m.cwd).strings(m.options).strings(m.extra)
        .i(m.width).i(m.height).i(m.digits).i(m.timeout).i(m.nice)
        .ok;
}

int pack(const Job &m)
{
    return Packer().i(m.unit).r(m.rect).i(m.first).i(m.last).i(m.step).i(m.threads).status;
}
bool unpack(Job &m)
{
    return Unpacker().i(m.unit).r(m.rect).i(m.first).i(m.last).i(m.step).i(m.threads).ok;
}

int pack(const FrameResult &m)
{
    return Packer()
        .i(m.unit).i(m.frame).r(m.rect).d(m.rays).d(m.seconds).i(m.aa_method).bytes(m.pixels)
        .status;
}
bool unpack(FrameResult &m)
{
    bool ok = Unpacker()
        .i(m.unit).i(m.frame).r(m.rect).d(m.rays).d(m.seconds).i(m.aa_method).bytes(m.pixels)
        .ok;
    return ok && m.rect.width() > 0 && m.rect.height() > 0 &&
           m.pixels.size() == size_t(m.rect.area()) * 3;
}

int pack(const Progress &m) { return Packer().i(m.unit).i(m.frame).i(m.done).i(m.total).status; }
bool unpack(Progress &m) { return Unpacker().i(m.unit).i(m.frame).i(m.done).i(m.total).ok; }

int pack(const UnitDone &m)
{
    return Packer().i(m.unit).i(m.status).i(m.frames).d(m.rays).d(m.seconds).status;
}
bool unpack(UnitDone &m)
{
    return Unpacker().i(m.unit).i(m.status).i(m.frames).d(m.rays).d(m.seconds).ok;
}

int pack(const Failure &m) { return Packer().i(m.unit).i(m.frame).i(m.status).s(m.message).status; }
bool unpack(Failure &m) { return Unpacker().i(m.unit).i(m.frame).i(m.status).s(m.message).ok; }

int pack(const Truncate &m) { return Packer().i(m.unit).i(m.last).status; }
bool unpack(Truncate &m) { return Unpacker().i(m.unit).i(m.last).ok; }

int pack_int(int v) { return Packer().i(v).status; }
bool unpack_int(int &v) { return Unpacker().i(v).ok; }

int pack_empty() { return Packer().status; }

} // namespace fc
