// Switches back to stock POV-Ray behaviour where povray-fc deliberately differs.
#ifndef POVRAYFC_COMPAT_H
#define POVRAYFC_COMPAT_H

namespace povrayfc {

// True when the environment sets POVRAYFC_STOCK_SHADOW_CACHE=1: the shadow cache then
// accepts hits as stock 3.7 does (see patch 0003). Frame coherence is not exact in that
// mode; it exists to show that this patch is the only source of pixel differences
// from Debian's povray. Read once.
bool StockShadowCache();

}  // namespace povrayfc

#endif
