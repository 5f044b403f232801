// master_liveness.cpp - fc-master's watch on real progress (liveness.h): a job not finished by
// its deadline gets a copy on another slave and its slave no more work; a frame stalled twice
// hangs, and a frame that hangs or keeps failing is given up, with its number and POV-Ray's
// last words: the render stops there, or with --keep-going goes on without it.
#include "master.h"

#include <algorithm>
#include <cstdio>

#include "clock.h"
#include "debug_log.h"
#include "protocol.h"
#include "text.h"

namespace fc {

namespace {

// Seconds the master waits for the last words of the slaves of a hanging frame.
const double kLastWordsWait = 3.0;

} // namespace

void Master::check_stalls()
{
    double t = now();
    struct Late {
        Job job;
        double seconds, deadline;
    };
    std::vector<Late> late;
    for (auto &kv : sched_->jobs()) {
        const Job &j = kv.second;
        if (!j.live || j.stalled || j.rendering < 0 || hangs_.count(j.index))
            continue;
        SlaveInfo *s = cluster_.slave(j.slave);
        if (!s || s->state != SlaveState::Ready)
            continue;
        double pixels = 0;
        for (int tile : j.tiles)
            pixels += double(sched_->tile(tile).area());
        double deadline = liveness_.deadline(j.slave, s->dtid, pixels, j.dup_of >= 0,
                                             costs_.fresh_cost());
        // An attempt begun after a job of its frame stalled decides whether the frame hangs.
        if (second_attempt(j))
            deadline = std::max(deadline, liveness_.hang_deadline(s->dtid, pixels));
        if (t - j.rendering > deadline)
            late.push_back({j, t - j.rendering, deadline});
    }
    for (const Late &l : late)
        if (!failed_)
            job_stalled(l.job, l.seconds, l.deadline);
}

bool Master::second_attempt(const Job &job) const
{
    double first = book_->first_stall(job.index);
    return first >= 0 && job.rendering >= first;
}

// A job is past its deadline: a copy goes to another slave, or, when no other slave can take
// one, the job is abandoned and runs again. The stall of an attempt begun after the frame's
// first stall (a copy, a re-render) means the frame hangs.
void Master::job_stalled(const Job &job, double seconds, double deadline)
{
    SlaveInfo *s = cluster_.slave(job.slave);
    std::string host = s ? s->host : "?";
    int frame = book_->number(job.index);
    // The jobs of one frame that ran side by side (its tiles on several slaves, all parsing
    // the same slow frame) stall together: only a later attempt's stall means it hangs.
    bool second = second_attempt(job);
    FrameBook::Trouble &trouble = book_->trouble(job.index);
    trouble.stalls++;
    if (trouble.first_stall < 0)
        trouble.first_stall = now();
    trouble.hosts.insert(host);
    debug_log("job %d (frame %d) stalled on t%x after %.1f s (deadline %.1f s)", job.id, frame,
              unsigned(job.slave), seconds, deadline);
    if (second) {
        frame_hangs(job.index);
        return;
    }
    bool other = false;
    for (auto &kv : cluster_.slaves())
        other = other || (kv.first != job.slave && kv.second.state == SlaveState::Ready &&
                          !sched_->suspended(kv.first));
    if (!other) {
        warn(strf("frame %d has not finished on host %s in %.0f s (its deadline, learned from "
                  "the run): it is rendered again", frame, host.c_str(), seconds));
        abandon(job);
        sched_->job_failed(job.id, now());
        dispatch();
        return;
    }
    warn(strf("frame %d has not finished on host %s in %.0f s (its deadline, learned from the "
              "run): another slave renders it too", frame, host.c_str(), seconds));
    std::vector<Job> cancel;
    sched_->stall(job.id, cancel);
    cancel_jobs(cancel);
    dispatch();
}

void Master::abandon(const Job &job)
{
    debug_log("FC_ABANDON job %d to t%x", job.id, unsigned(job.slave));
    if (pack_int(job.id) >= 0)
        send_packed(job.slave, FC_ABANDON);
    stats_.job_ended(job.id, "abandoned");
}

// Frame index did not finish on two slaves (or twice on the only one): every job of it is
// abandoned, and its slaves' replies bring POV-Ray's last words for the verdict.
void Master::frame_hangs(int index)
{
    Hang &h = hangs_[index];
    h.until = now() + kLastWordsWait;
    for (auto &kv : sched_->jobs()) {
        const Job &j = kv.second;
        if (!j.live || j.index != index)
            continue;
        SlaveInfo *s = cluster_.slave(j.slave);
        h.hosts.push_back(s ? s->host : "?");
        if (s && s->state == SlaveState::Ready) {
            abandon(j);
            h.jobs.insert(j.id);
        }
    }
    for (const std::string &host : book_->trouble(index).hosts)
        if (std::find(h.hosts.begin(), h.hosts.end(), host) == h.hosts.end())
            h.hosts.push_back(host);
    conclude_hangs(false);
}

// A slave's reply to FC_ABANDON: its renderer is stopped; POV-Ray's last words came with it.
void Master::on_abandoned(const Failure &f, const std::string &host)
{
    int index = book_->index_of(f.frame);
    auto it = hangs_.find(index);
    if (it == hangs_.end() || !it->second.jobs.erase(f.job))
        return;     // a job abandoned to run again elsewhere: its work is queued already
    it->second.words += "  on " + host + ":\n";
    std::string words = f.message;
    size_t pos = 0;
    while (pos < words.size()) {
        size_t nl = words.find('\n', pos);
        std::string line = words.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
        it->second.words += "    " + line + "\n";
        pos = nl == std::string::npos ? words.size() : nl + 1;
    }
    conclude_hangs(false);
}

// Give up the hanging frames whose last words are all in, or waited for long enough (all:
// every one).
void Master::conclude_hangs(bool all)
{
    double t = now();
    for (auto it = hangs_.begin(); it != hangs_.end() && !failed_;) {
        const Hang &h = it->second;
        if (!all && !h.jobs.empty() && t < h.until) {
            ++it;
            continue;
        }
        int index = it->first;
        std::string hosts;
        for (const std::string &name : h.hosts)
            hosts += (hosts.empty() ? "" : ", ") + name;
        std::string why = strf("frame %d hangs: it did not finish within its deadline on %s %s; "
                               "POV-Ray's last words:\n%s",
                               book_->number(index), h.hosts.size() > 1 ? "hosts" : "host",
                               hosts.c_str(), h.words.empty() ? "  (no answer)\n" : h.words.c_str());
        it = hangs_.erase(it);
        give_up_frame(index, why);
    }
}

// A frame that cannot be rendered: the render stops with why, or, with --keep-going, goes on
// without it (the frame gets no file and is listed at the end).
void Master::give_up_frame(int index, const std::string &why)
{
    if (!opt_.keep_going) {
        fatal(why);
        return;
    }
    report_.clear_line();
    fprintf(stderr, "fc-master: %s", why.c_str());
    if (why.empty() || why.back() != '\n')
        fputc('\n', stderr);
    fprintf(stderr, "fc-master: frame %d is left without a file; --keep-going renders the "
                    "others\n", book_->number(index));
    book_->give_up(index, why);
    std::vector<Job> cancel;
    sched_->frame_settled(index, cancel, now());
    cancel_jobs(cancel);
    dispatch();
}

} // namespace fc
