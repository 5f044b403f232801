// freed_memory.h - how fc-master and fc-slave ask the allocator to treat frame buffers.
#pragma once

namespace fc {

// Tell glibc's allocator to keep freed memory for the next allocation instead of giving it
// back to the kernel. A coordinator's buffers are frame-sized and come and go every frame;
// by default glibc unmapped or trimmed each at its free (its thresholds follow the largest
// block freed) and the next frame faulted every page in again: at 1280x960 two thirds of
// fc-master's CPU. What is kept is bounded by the frames in flight, which the process holds
// at its peak anyway.
void keep_freed_memory();

} // namespace fc
