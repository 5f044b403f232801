// Writes which pixels a frame traced, as an image, for figures and checks (Figure 2).
#ifndef POVRAYFC_RETRACE_MASK_H
#define POVRAYFC_RETRACE_MASK_H

#include <string>

#include "povrayfc/dirty_mask.h"

namespace povrayfc {

// Writes `traced` as an 8-bit greyscale PNG (255 = traced, 0 = reused or outside the
// render area) to `path`, through OpenImageIO, via a temporary name renamed into place.
// Returns false with `error` set when it cannot.
bool WriteRetraceMask(const std::string &path, const DirtyMask &traced, std::string &error);

}  // namespace povrayfc

#endif
