// image_io.cpp - loading fc-image.so (OpenImageIO) on demand, in the background.
#include "image_io.h"

#include <dlfcn.h>

#include <mutex>
#include <thread>

#include "util.h"

namespace fc {

namespace {

typedef int (*WriteTarga)(const char *, int, int, const unsigned char *, char *, size_t);
typedef int (*ImageSize)(const char *, int *, int *, int *);

struct Plugin {
    std::thread loader;
    std::mutex mutex;
    bool started = false;
    WriteTarga write = nullptr;
    ImageSize size = nullptr;
    std::string error;

    // A master that ends early (bad scene) must not leave the loader running.
    ~Plugin()
    {
        if (loader.joinable())
            loader.join();
    }

    void load()
    {
        std::string path = self_dir() + "/fc-image.so";
        void *h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!h) {
            error = std::string("cannot load ") + dlerror();
            return;
        }
        write = reinterpret_cast<WriteTarga>(dlsym(h, "fc_image_write_targa"));
        size = reinterpret_cast<ImageSize>(dlsym(h, "fc_image_size"));
        if (!write || !size)
            error = path + " lacks fc_image_write_targa or fc_image_size";
    }
};

Plugin &plugin()
{
    static Plugin p;
    return p;
}

// Wait for the background load (or load now).
Plugin &ready()
{
    Plugin &p = plugin();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (!p.started) {
        p.started = true;
        p.load();
    } else if (p.loader.joinable()) {
        p.loader.join();
    }
    return p;
}

} // namespace

void preload_image_io()
{
    Plugin &p = plugin();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.started)
        return;
    p.started = true;
    p.loader = std::thread([&p] { p.load(); });
}

bool write_targa(const std::string &path, int width, int height, const uint8_t *rgb,
                 std::string &err)
{
    Plugin &p = ready();
    if (!p.write) {
        err = p.error;
        return false;
    }
    char msg[1024] = "";
    if (!p.write(path.c_str(), width, height, rgb, msg, sizeof msg)) {
        err = "writing " + path + ": " + msg;
        return false;
    }
    return true;
}

bool image_size(const std::string &path, int &width, int &height, int &channels)
{
    Plugin &p = ready();
    return p.size && p.size(path.c_str(), &width, &height, &channels) != 0;
}

} // namespace fc
