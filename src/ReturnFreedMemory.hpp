#pragma once
// The process's heap kept small between the phases of a run.
//
// returnFreedMemory: gives the free pages inside the heap back to the system (glibc's
// malloc_trim). Arrays of a large mesh's nodes (24 MB at 10⁶ points) fall under glibc's
// dynamic mmap threshold once one of that size has been freed, so later ones live in the main
// heap, and freeing them leaves their pages resident: the solve's work arrays would still count
// in the peak of the quality check and the output that follow it, whose own large arrays come
// as fresh pages. Elsewhere a no-op.

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

// One heap for every thread (glibc's M_ARENA_MAX 1), for a program's main. The solver's threads
// allocate inside their parallel loops now and then; each thread's own arena then keeps what it
// freed, and on the 10⁶-cell cube with two threads that was 61 MiB more at the peak than with
// one, for no measurable speed (rbmMoveMesh: 1 989 against 1 928 MiB, CPU time within noise).
// Not for the OpenFOAM plugin: the host process's allocator is the host's. Elsewhere a no-op.
inline void useOneHeapForAllThreads()
{
#if defined(__GLIBC__)
    mallopt(M_ARENA_MAX, 1);
#endif
}

} // namespace rbm
