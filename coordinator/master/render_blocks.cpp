// render_blocks.cpp - see render_blocks.h.
#include "render_blocks.h"

#include <cstdlib>

namespace fc {

bool pixels_depend_on_block_grid(const ResolvedOptions &ini)
{
    // Create_Ini leaves out options at their defaults: antialiasing off, method 1.
    return option_is_on(resolved_value(ini, "Antialias", "off")) &&
           atoi(resolved_value(ini, "Sampling_Method", "1").c_str()) == 1;
}

int slave_render_block(const ResolvedOptions &ini, int tile)
{
    if (tile <= 0 || pixels_depend_on_block_grid(ini))
        return 0;
    // 32: POV-Ray's default (view.cpp).
    int current = atoi(resolved_value(ini, "Render_Block_Size", "32").c_str());
    if (current >= 4 && tile % current == 0)
        return 0;
    for (int d = kLargestBlock; d >= kSmallestBlock; d--)
        if (tile % d == 0)
            return d;
    return 0;
}

} // namespace fc
