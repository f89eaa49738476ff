#pragma once
// Gives the free pages inside the heap back to the system (glibc's malloc_trim). Arrays of a
// large mesh's nodes (24 MB at 10⁶ points) fall under glibc's dynamic mmap threshold once one of
// that size has been freed, so later ones live in the main heap, and freeing them leaves their
// pages resident: the solve's work arrays would still count in the peak of the quality check
// and the output that follow it, whose own large arrays come as fresh pages. Elsewhere a no-op.

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rbm {

inline void returnFreedMemory()
{
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

} // namespace rbm
