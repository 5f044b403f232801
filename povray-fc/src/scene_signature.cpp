// Hand-over of a frame's scene signature from the parser thread to the render side.
#include "povrayfc/scene_signature.h"

#include <map>
#include <mutex>
#include <utility>

namespace povrayfc {

namespace {

// POV-Ray parses a frame, then renders it, then parses the next, so there is normally
// at most one signature waiting. Keyed by scene so that a signature is never taken for
// another scene; a few are kept in case several scenes are alive at once (the oldest
// published goes first when there are more).
constexpr std::size_t kMaxWaiting = 8;

struct Waiting {
    SceneSignature signature;
    unsigned long long serial = 0;
};

std::mutex waitingMutex;
std::map<const void *, Waiting> waiting;
unsigned long long nextSerial = 0;

}  // namespace

void PublishSceneSignature(const void *sceneKey, SceneSignature signature) {
    std::lock_guard<std::mutex> lock(waitingMutex);
    Waiting &slot = waiting[sceneKey];
    slot.signature = std::move(signature);
    slot.serial = ++nextSerial;
    while (waiting.size() > kMaxWaiting) {
        auto oldest = waiting.begin();
        for (auto it = waiting.begin(); it != waiting.end(); ++it)
            if (it->second.serial < oldest->second.serial) oldest = it;
        waiting.erase(oldest);
    }
}

bool TakeSceneSignature(const void *sceneKey, SceneSignature &out) {
    std::lock_guard<std::mutex> lock(waitingMutex);
    auto found = waiting.find(sceneKey);
    if (found == waiting.end()) return false;
    out = std::move(found->second.signature);
    waiting.erase(found);
    return true;
}

}  // namespace povrayfc
