// The re-traced pixel mask of a frame, written by the povrayfc-mask.so plugin.
#include "povrayfc/retrace_mask.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

namespace povrayfc {

namespace {

using WriteMaskFn = int (*)(const char *, int, int, const unsigned char *, char *, std::size_t);

// The plugin beside the running executable, or $POVRAYFC_MASK_PLUGIN.
std::string PluginPath() {
    if (const char *env = std::getenv("POVRAYFC_MASK_PLUGIN")) return env;
    char exe[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) return "povrayfc-mask.so";
    std::string dir(exe, std::size_t(n));
    return dir.substr(0, dir.rfind('/') + 1) + "povrayfc-mask.so";
}

WriteMaskFn LoadWriter(std::string &error) {
    static std::once_flag once;
    static WriteMaskFn writer = nullptr;
    static std::string loadError;
    std::call_once(once, [] {
        const std::string path = PluginPath();
        void *handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            loadError = std::string("cannot load ") + dlerror();
            return;
        }
        writer = reinterpret_cast<WriteMaskFn>(dlsym(handle, "povrayfc_write_mask"));
        if (!writer) loadError = path + ": no povrayfc_write_mask";
    });
    error = loadError;
    return writer;
}

}  // namespace

bool WriteRetraceMask(const std::string &path, const DirtyMask &traced, std::string &error) {
    WriteMaskFn writer = LoadWriter(error);
    if (!writer) {
        error = path + ": " + error;
        return false;
    }
    const int w = traced.Width(), h = traced.Height();
    std::vector<unsigned char> pixels(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) pixels[std::size_t(y) * w + x] = traced.Test(x, y) ? 255 : 0;
    // The temporary keeps the .png extension so OpenImageIO picks the format.
    const std::string temporary = path + ".tmp.png";
    char message[512] = "";
    if (!writer(temporary.c_str(), w, h, pixels.data(), message, sizeof message)) {
        error = path + ": " + message;
        std::remove(temporary.c_str());
        return false;
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        error = path + ": cannot rename the temporary file into place";
        std::remove(temporary.c_str());
        return false;
    }
    return true;
}

}  // namespace povrayfc
