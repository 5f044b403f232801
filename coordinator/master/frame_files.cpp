// frame_files.cpp - the frames on disk (see frame_files.h).
#include "frame_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "durable_write.h"
#include "files.h"
#include "hashes.h"
#include "povray_probe.h"
#include "text.h"

namespace fc {

FrameFiles::FrameFiles(OutputDir &dir, const OutputFormat &format, const std::string &stem,
                       int digits, int width, int height, const std::vector<int> &frames)
    : dir_(dir), format_(format), stem_(stem), digits_(digits), width_(width), height_(height),
      frames_(frames)
{
}

std::string FrameFiles::file_name(int index) const
{
    return frame_file_name(stem_, digits_, frames_[size_t(index)], format_.ext);
}

std::string FrameFiles::final_path(int index) const
{
    return dir_.path() + "/" + file_name(index);
}

std::string FrameFiles::temp_path(int index) const
{
    return final_path(index) + ".fc-tmp";
}

uint64_t FrameFiles::pixels_hash(const std::vector<uint8_t> &samples, bool words)
{
    return words ? hash_words(samples.data(), samples.size())
                 : hash_bytes(samples.data(), samples.size());
}

bool FrameFiles::verify(int index, bool adopt, std::string &why, std::vector<uint8_t> &pixels) const
{
    std::string path = final_path(index);
    why.clear();
    if (!file_exists(path))
        return false;
    int w = 0, h = 0, channels = 0;
    std::string err;
    if (!read_image(path, format_.pixels, w, h, channels, pixels, err)) {
        why = "it does not decode completely (" + err + ")";
        return false;
    }
    if (w != width_ || h != height_) {
        why = strf("it is %dx%d, not %dx%d", w, h, width_, height_);
        return false;
    }
    if (format_.fixed_size) {
        // A reader may fill in what a short file lacks; an uncompressed Targa holds at least
        // its 18-byte header and every pixel (whoever wrote it: POV-Ray adds no footer).
        size_t want = 18 + size_t(width_) * size_t(height_) * 3;
        struct stat st;
        if (stat(path.c_str(), &st) == 0 && size_t(st.st_size) < want) {
            why = strf("it is cut short (%lld of at least %zu bytes)", (long long)st.st_size, want);
            return false;
        }
    }
    uint64_t recorded = 0;
    bool words = true;
    if (dir_.recorded(base_name(path), recorded, words)) {
        if (recorded != pixels_hash(pixels, words)) {
            why = "its pixels are not those fc-master wrote";
            return false;
        }
        return true;
    }
    if (!adopt) {
        why = "this run's record does not list it";
        return false;
    }
    return true;
}

void FrameFiles::remove_stale_temps() const
{
    for (size_t i = 0; i < frames_.size(); i++)
        unlink(temp_path(int(i)).c_str());
}

bool FrameFiles::store(int index, const std::vector<uint8_t> &bytes, uint64_t samples_hash,
                       const FrameInputs &inputs, bool &disk_full, std::string &err)
{
    disk_full = false;
    std::string tmp = temp_path(index), dst = final_path(index);
    if (!write_file_durably(tmp, bytes.data(), bytes.size(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    // Recorded before it gets its name: a master killed in between leaves a record whose
    // file is missing or another (resume renders it again), never a complete frame under its
    // final name that resume would not recognise and render again.
    if (!dir_.record(base_name(dst), samples_hash, inputs, err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        unlink(tmp.c_str());
        return false;
    }
    // Only a complete file gets the final name (rename replaces a damaged one atomically).
    if (rename(tmp.c_str(), dst.c_str()) != 0) {
        sys_fail(err, "rename " + tmp + " to " + dst);
        unlink(tmp.c_str());
        return false;
    }
    if (!sync_dir(dir_.path(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    return true;
}

} // namespace fc
