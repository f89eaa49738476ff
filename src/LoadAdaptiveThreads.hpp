#pragma once
// rbmMoveMesh's thread count on a machine it shares: before every time step, the cores other
// processes kept busy during the last step are measured and rbm's threaded loops use only the
// cores left (at least 1, at most the policy's count, ThreadCount.hpp).
//
// Why: a team of OpenMP threads meets at a barrier after every loop, so one thread that waits
// for a busy core holds up the others; with every core busy with other work, two threads make
// a time series several times slower in wall time than one (docs/rbmMoveMesh.md, "Threads").
// The measure is the machine's busy time (/proc/stat) minus this process's own CPU time
// (getrusage) over the last step: this process's own threads are not counted as load, so a
// long run on a dedicated machine keeps every core (a rule on the load average would count
// them as load and give cores away). Results do not depend on the thread count.
//
// Only where the policy chose more than one thread and OMP_NUM_THREADS is unset (a user who
// sets it gets exactly that); elsewhere, and without /proc/stat, it changes nothing.

#include <chrono>

namespace rbm {

class LoadAdaptiveThreads {
public:
    // `most`: the thread count the policy gave (applyThreadCountPolicy).
    explicit LoadAdaptiveThreads(int most);

    // Measures the other processes' load since the last call (or construction) and sets the
    // thread count for the next loops; returns it.
    int update();

    // The cores others kept busy over the last measured interval (0 before one).
    double otherLoad() const { return otherLoad_; }

    bool active() const { return active_; }

private:
    struct Sample {
        double busySeconds = 0.0;   // all cores' non-idle time since boot
        double ownSeconds = 0.0;    // this process's user + system time
        std::chrono::steady_clock::time_point at;
        bool valid = false;
    };
    static Sample sample();

    int most_ = 1;
    int cores_ = 1;
    bool active_ = false;
    double otherLoad_ = 0.0;
    int current_ = 1;
    Sample last_;
};

} // namespace rbm
