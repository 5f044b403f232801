// The thread-local recorder pointer the tracing hooks test.
#include "povrayfc/ray_recording.h"

namespace povrayfc {
namespace detail {

thread_local SampleRecorder *tlsRecorder = nullptr;

}  // namespace detail
}  // namespace povrayfc
