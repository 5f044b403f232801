// image_writer_client.cpp - talking to fc-image-writer (see image_writer_client.h; the
// protocol is in image-writer/protocol.h).
#include "image_writer_client.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>

#include "child_process.h"
#include "clock.h"
#include "debug_log.h"
#include "files.h"
#include "host_info.h"
#include "image-writer/protocol.h"
#include "text.h"

namespace fc {

namespace {

using fc_image_writer::kReplyMagic;
using fc_image_writer::kRequestMagic;
// A frame takes the helper milliseconds; this bound only keeps a hung helper from hanging
// the master.
const double kTimeout = 60.0;

struct Helper {
    std::mutex mutex;           // encoding may be asked from the loop and at the end
    Child child;
    int requests = -1, replies = -1;
    bool failed = false;
    std::string why;

    ~Helper() { stop(); }

    bool start(std::string &err)
    {
        int req[2], rep[2];
        if (pipe2(req, O_CLOEXEC) != 0)
            return sys_fail(err, "pipe2");
        if (pipe2(rep, O_CLOEXEC) != 0) {
            close(req[0]);
            close(req[1]);
            return sys_fail(err, "pipe2");
        }
        bool ok = start_child({self_dir() + "/fc-image-writer"}, "", 0, child, err,
                              {{fc_image_writer::kRequestFd, req[0]},
                               {fc_image_writer::kReplyFd, rep[1]}});
        close(req[0]);
        close(rep[1]);
        if (!ok) {
            close(req[1]);
            close(rep[0]);
            return false;
        }
        requests = req[1];
        replies = rep[0];
        debug_log("fc-image-writer %d started", int(child.pid));
        return true;
    }

    void stop()
    {
        if (requests >= 0)
            close(requests);
        if (replies >= 0)
            close(replies);
        requests = replies = -1;
        if (child.pid > 0) {
            int status = 0;
            if (!wait_child(child, 1.0, status))
                kill_child(child);
            child.pid = -1;
        }
        if (child.fd >= 0) {
            close(child.fd);
            child.fd = -1;
        }
    }

    // What the helper said on its stdout/stderr, for an error message.
    std::string said()
    {
        std::vector<std::string> lines;
        read_child(child, lines);
        return lines.empty() ? "" : " (" + trim(lines.back()) + ")";
    }

    // Wait until fd is ready for events, up to the deadline; false with err.
    bool wait_ready(int fd, short events, double deadline, std::string &err)
    {
        for (;;) {
            double left = deadline - now();
            if (left <= 0) {
                err = "fc-image-writer did not answer within " + strf("%.0f s", kTimeout);
                return false;
            }
            struct pollfd p = {fd, events, 0};
            int r = poll(&p, 1, int(left * 1000) + 1);
            if (r < 0 && errno == EINTR)
                continue;
            if (r < 0)
                return sys_fail(err, "poll");
            if (r > 0)
                return true;
        }
    }

    // Write (to the requests) or read (from the replies) all n bytes by the deadline; false
    // with err.
    bool transfer(bool sending, void *buf, size_t n, double deadline, std::string &err)
    {
        int fd = sending ? requests : replies;
        char *p = static_cast<char *>(buf);
        while (n > 0) {
            if (!wait_ready(fd, sending ? POLLOUT : POLLIN, deadline, err))
                return false;
            ssize_t done = sending ? write(fd, p, n) : read(fd, p, n);
            if (done < 0 && (errno == EINTR || errno == EAGAIN))
                continue;
            if (done <= 0) {
                err = (sending ? "fc-image-writer stopped taking frames"
                               : "fc-image-writer ended without an answer") + said();
                return false;
            }
            p += done;
            n -= size_t(done);
        }
        return true;
    }

    // Send req and its payload, and take the answer into out, which may be at most max_reply
    // bytes; false with err, after which the helper is not used again.
    bool ask(const fc_image_writer::Request &req, const void *payload, size_t bytes,
             size_t max_reply, std::vector<uint8_t> &out, std::string &err)
    {
        if (failed) {
            err = why;
            return false;
        }
        if (child.pid <= 0 && !start(err)) {
            fail(err);
            return false;
        }
        double deadline = now() + kTimeout;
        fc_image_writer::Reply head;
        if (!transfer(true, const_cast<fc_image_writer::Request *>(&req), sizeof req, deadline,
                      err) ||
            !transfer(true, const_cast<void *>(payload), bytes, deadline, err) ||
            !transfer(false, &head, sizeof head, deadline, err)) {
            fail(err);
            return false;
        }
        if (head.magic != kReplyMagic || head.size > max_reply) {
            err = "fc-image-writer sent a malformed reply";
            fail(err);
            return false;
        }
        out.resize(size_t(head.size));
        if (!transfer(false, out.data(), out.size(), deadline, err)) {
            fail(err);
            return false;
        }
        if (head.ok != 1) {
            err = "fc-image-writer: " + std::string(out.begin(), out.end());
            out.clear();
            fail(err);
            return false;
        }
        return true;
    }

    void fail(const std::string &reason)
    {
        failed = true;
        why = reason;
        stop();
    }
};

Helper &helper()
{
    static Helper h;
    return h;
}

} // namespace

bool image_writer_present()
{
    // Asked for every frame: the answer for the whole run.
    static const bool present = is_executable(self_dir() + "/fc-image-writer");
    return present;
}

bool writer_encode_targa(int width, int height, bool rle, double file_gamma, const uint8_t *rgb,
                         std::vector<uint8_t> &out, std::string &err)
{
    fc_image_writer::Request req = {kRequestMagic, fc_image_writer::kEncodeTarga, width, height,
                                    rle ? 1 : 0, float(file_gamma), Diffusion()};
    size_t bytes = size_t(width) * size_t(height) * 3;
    Helper &h = helper();
    std::lock_guard<std::mutex> lock(h.mutex);
    // A Targa file is its pixels plus at most a byte per 128 of them and 1 KiB of header
    // and footer; a message is short.
    return h.ask(req, rgb, bytes, bytes + bytes / 128 + 4096, out, err);
}

bool writer_dither(int width, int height, const Diffusion &diffusion, const float *values,
                   std::vector<uint8_t> &rgb, std::string &err)
{
    fc_image_writer::Request req = {kRequestMagic, fc_image_writer::kDither, width, height, 0,
                                    0.0f, diffusion};
    size_t samples = size_t(width) * size_t(height) * 3;
    Helper &h = helper();
    std::lock_guard<std::mutex> lock(h.mutex);
    if (!h.ask(req, values, samples * sizeof(float), samples, rgb, err))
        return false;
    if (rgb.size() != samples) {
        err = "fc-image-writer sent a malformed reply";
        h.fail(err);
        return false;
    }
    return true;
}

void stop_image_writer()
{
    Helper &h = helper();
    std::lock_guard<std::mutex> lock(h.mutex);
    h.stop();
}

} // namespace fc
