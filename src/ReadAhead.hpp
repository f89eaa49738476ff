#pragma once
// Asking the memory system for an array's bytes a little before a loop reads them.
//
// Why: rbm's per-step passes (the back-substitutions with K's factor, the planar kernels of
// the reduced Newton solver) each stream megabytes that are no longer in cache from the pass
// before, in short runs per supernode or per node with work in between. The processor's own
// prefetching does not keep up with such short runs, so those loops request the bytes about
// 2 KB ahead (the distances are chosen in SparseCholesky.cpp and PlanarReducedKernels.cpp;
// the effect on a time step shows in rbmBenchmark's airfoil pitching series). A request is a
// hint only (it never faults and changes no result).

#include <algorithm>
#include <cstddef>

namespace rbm {

class ReadAhead {
public:
    static constexpr std::ptrdiff_t cacheLineBytes = 64;

    // An array of `totalBytes` bytes from `base`, read upwards (first byte first) or downwards,
    // with requests `lookaheadBytes` beyond what the loop has reached.
    ReadAhead(const void* base, std::ptrdiff_t totalBytes, std::ptrdiff_t lookaheadBytes, bool downwards = false)
        : base_(static_cast<const char*>(base)), total_(totalBytes), lookahead_(lookaheadBytes),
          downwards_(downwards), requested_(downwards ? totalBytes : 0)
    {
    }

    // The loop is about to read the bytes [begin, end): request everything up to
    // lookaheadBytes beyond them (upwards: beyond end; downwards: below begin). Requests
    // already made are not repeated; a jump (a thread's first element of a statically
    // scheduled loop) starts the requests there.
    void reach(std::ptrdiff_t begin, std::ptrdiff_t end)
    {
        if (!downwards_) {
            requested_ = std::max(requested_, begin);
            const std::ptrdiff_t target = std::min(total_, end + lookahead_);
            for (; requested_ < target; requested_ += cacheLineBytes) __builtin_prefetch(base_ + requested_, 0, 0);
        } else {
            requested_ = std::min(requested_, end);
            const std::ptrdiff_t target = std::max<std::ptrdiff_t>(0, begin - lookahead_);
            for (; requested_ > target; requested_ -= cacheLineBytes)
                __builtin_prefetch(base_ + std::max<std::ptrdiff_t>(0, requested_ - cacheLineBytes), 0, 0);
        }
    }

private:
    const char* base_;
    std::ptrdiff_t total_;
    std::ptrdiff_t lookahead_;
    bool downwards_;
    std::ptrdiff_t requested_;
};

} // namespace rbm
