#include "gi/platform/memory.h"

#include <malloc.h>

namespace gi {

void keepFreedMemory() {
    static const bool done = [] {
        mallopt(M_MMAP_THRESHOLD, 32 << 20);
        mallopt(M_TRIM_THRESHOLD, 256 << 20);
        return true;
    }();
    (void)done;
}

}  // namespace gi
