// Switches back to stock POV-Ray behaviour, read from the environment once.
#include "povrayfc/compat.h"

#include <cstdlib>
#include <cstring>

namespace povrayfc {

bool StockShadowCache() {
    static const bool stock = [] {
        const char *value = std::getenv("POVRAYFC_STOCK_SHADOW_CACHE");
        return value != nullptr && std::strcmp(value, "1") == 0;
    }();
    return stock;
}

}  // namespace povrayfc
