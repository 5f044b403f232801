// Hand-over of a frame's scene signature from the parser thread to the render side.
#include "povrayfc/scene_signature.h"

#include <mutex>
#include <utility>

namespace povrayfc {

namespace {
// One slot: POV-Ray parses a frame, then renders it, then parses the next.
std::mutex slotMutex;
const void *slotKey = nullptr;
SceneSignature slot;
bool slotFull = false;
}  // namespace

void PublishSceneSignature(const void *sceneKey, SceneSignature signature) {
    std::lock_guard<std::mutex> lock(slotMutex);
    slotKey = sceneKey;
    slot = std::move(signature);
    slotFull = true;
}

bool TakeSceneSignature(const void *sceneKey, SceneSignature &out) {
    std::lock_guard<std::mutex> lock(slotMutex);
    if (!slotFull || slotKey != sceneKey) return false;
    out = std::move(slot);
    slotFull = false;
    return true;
}

}  // namespace povrayfc
