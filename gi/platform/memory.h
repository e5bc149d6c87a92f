// The process's heap policy for a software GL driver (issue 17 item 5).
#pragma once

namespace gi {

// Keeps memory the process frees for reuse instead of returning it to the kernel at once.
// llvmpipe allocates and frees its vertex buffers (megabytes) on every draw; glibc's default
// hands such blocks back (mmap above a dynamic threshold, trimming the heap's top above
// 128 KiB), so every frame faulted the same pages in again: about 9,200 page faults per Sponza
// frame, and the G-buffer pass took twice as long (112 -> 48 ms at 80x60; the pixels are the
// same). Allocations below 32 MiB come from the heap, which is trimmed only when 256 MiB lie
// free at its top. Called once per process before the first GL context (EGLContextHeadless);
// later calls do nothing.
void keepFreedMemory();

}  // namespace gi
