// The thread-local pointers the tracing hooks test.
#include "povrayfc/ray_recording.h"
#include "povrayfc/tie_watch.h"

namespace povrayfc {
namespace detail {

thread_local SampleRecorder *tlsRecorder = nullptr;
thread_local TieWatch *tlsTieWatch = nullptr;
thread_local ShadowRun *tlsShadowRun = nullptr;

}  // namespace detail
}  // namespace povrayfc
