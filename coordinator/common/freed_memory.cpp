// freed_memory.cpp - the allocator keeps frame buffers (see freed_memory.h).
#include "freed_memory.h"

#include <malloc.h>

#include <climits>

namespace fc {

void keep_freed_memory()
{
    // 32 MiB is the largest mmap threshold glibc accepts: blocks up to it come from the heap.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
}

} // namespace fc
