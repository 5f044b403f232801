// image_codec.cpp - OpenImageIO through fc-image.so, loaded on demand in the background (see
// image_codec.h).
#include "image_codec.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <thread>

#include "debug_log.h"
#include "host_info.h"

namespace fc {

namespace {

typedef int (*EncodeFn)(const char *, int, int, int, const void *, const char *,
                        unsigned char **, size_t *, char *, size_t);
typedef void (*FreeFn)(void *);
typedef int (*ReadFn)(const char *, int, int *, int *, int *, void **, char *, size_t);
typedef void (*ToHalfFn)(const float *, uint16_t *, size_t);
typedef void (*FromHalfFn)(const uint16_t *, float *, size_t);

struct Plugin {
    std::thread loader;
    std::mutex mutex;
    bool started = false;
    EncodeFn encode = nullptr;
    FreeFn free = nullptr;
    ReadFn read = nullptr;
    ToHalfFn to_half = nullptr;
    FromHalfFn from_half = nullptr;
    std::string error;
    std::atomic<bool> loading{false};   // the background load runs

    // A master that ends early (bad scene) must not leave the loader running.
    ~Plugin()
    {
        if (loader.joinable())
            loader.join();
    }

    void load()
    {
        std::string path = self_dir() + "/fc-image.so";
        debug_log("loading OpenImageIO (%s)", path.c_str());
        void *h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!h) {
            error = std::string("cannot load ") + dlerror();
            return;
        }
        encode = reinterpret_cast<EncodeFn>(dlsym(h, "fc_image_encode"));
        free = reinterpret_cast<FreeFn>(dlsym(h, "fc_image_free"));
        read = reinterpret_cast<ReadFn>(dlsym(h, "fc_image_read"));
        to_half = reinterpret_cast<ToHalfFn>(dlsym(h, "fc_image_float_to_half"));
        from_half = reinterpret_cast<FromHalfFn>(dlsym(h, "fc_image_half_to_float"));
        if (!encode || !free || !read || !to_half || !from_half) {
            error = path + " is from another version of fc-master (a function is missing)";
            encode = nullptr;
        }
    }
};

Plugin &plugin()
{
    static Plugin p;
    return p;
}

// Wait for the background load (or load now); false with err when the plugin is unusable.
bool ready(Plugin *&out, std::string &err)
{
    Plugin &p = plugin();
    {
        std::lock_guard<std::mutex> lock(p.mutex);
        if (!p.started) {
            p.started = true;
            p.load();
        } else if (p.loader.joinable()) {
            p.loader.join();
        }
    }
    out = &p;
    if (!p.encode) {
        err = p.error;
        return false;
    }
    return true;
}

} // namespace

size_t pixel_type_bytes(PixelType t)
{
    return t == PixelType::U8 ? 1 : 2;
}

void preload_image_io()
{
    Plugin &p = plugin();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.started)
        return;
    p.started = true;
    p.loading = true;
    p.loader = std::thread([&p] {
        p.load();
        p.loading = false;
    });
}

bool image_io_loading()
{
    return plugin().loading;
}

bool image_io_ready()
{
    Plugin &p = plugin();
    std::lock_guard<std::mutex> lock(p.mutex);
    return p.started && !p.loading;
}

void wait_image_io()
{
    Plugin &p = plugin();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.loader.joinable())
        p.loader.join();
}

bool encode_with_image_io(const std::string &format, const std::string &compression, int width,
                          int height, PixelType type, const void *pixels,
                          std::vector<uint8_t> &out, std::string &err)
{
    Plugin *p = nullptr;
    if (!ready(p, err))
        return false;
    unsigned char *bytes = nullptr;
    size_t size = 0;
    char msg[1024] = "";
    if (!p->encode(format.c_str(), width, height, int(type), pixels, compression.c_str(), &bytes,
                   &size, msg, sizeof msg)) {
        err = "encoding " + format + ": " + msg;
        return false;
    }
    out.assign(bytes, bytes + size);
    p->free(bytes);
    return true;
}

bool read_image(const std::string &path, PixelType type, int &width, int &height, int &channels,
                std::vector<uint8_t> &pixels, std::string &err)
{
    Plugin *p = nullptr;
    if (!ready(p, err))
        return false;
    void *buf = nullptr;
    char msg[1024] = "";
    if (!p->read(path.c_str(), int(type), &width, &height, &channels, &buf, msg, sizeof msg)) {
        err = msg;
        return false;
    }
    size_t n = size_t(width) * size_t(height) * 3 * pixel_type_bytes(type);
    const uint8_t *b = static_cast<const uint8_t *>(buf);
    pixels.assign(b, b + n);
    p->free(buf);
    return true;
}

bool floats_to_half(const float *in, uint16_t *out, size_t n, std::string &err)
{
    Plugin *p = nullptr;
    if (!ready(p, err))
        return false;
    p->to_half(in, out, n);
    return true;
}

bool half_to_floats(const uint16_t *in, float *out, size_t n, std::string &err)
{
    Plugin *p = nullptr;
    if (!ready(p, err))
        return false;
    p->from_half(in, out, n);
    return true;
}

} // namespace fc
