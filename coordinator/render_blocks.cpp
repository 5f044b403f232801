// render_blocks.cpp - see render_blocks.h.
#include "render_blocks.h"

#include <cstdlib>
#include <strings.h>

namespace fc {

namespace {

bool is_on(const std::string &v)
{
    static const char *const kTrue[] = {"on", "true", "yes", "1"};
    for (const char *t : kTrue)
        if (strcasecmp(v.c_str(), t) == 0)
            return true;
    return false;
}

int int_option(const ResolvedOptions &ini, const char *key, int fallback)
{
    auto it = ini.find(key);
    return it == ini.end() ? fallback : atoi(it->second.c_str());
}

} // namespace

bool pixels_depend_on_block_grid(const ResolvedOptions &ini)
{
    auto aa = ini.find("Antialias");
    // Create_Ini leaves out options at their defaults: antialiasing off, method 1.
    return aa != ini.end() && is_on(aa->second) && int_option(ini, "Sampling_Method", 1) == 1;
}

int slave_render_block(const ResolvedOptions &ini, int tile)
{
    if (tile <= 0 || pixels_depend_on_block_grid(ini))
        return 0;
    int current = int_option(ini, "Render_Block_Size", kDefaultRenderBlock);
    if (current >= 4 && tile % current == 0)
        return 0;
    for (int d = kLargestBlock; d >= kSmallestBlock; d--)
        if (tile % d == 0)
            return d;
    return 0;
}

} // namespace fc
