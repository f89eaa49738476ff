#pragma once
// For tests that change OMP_NUM_THREADS or rbm's thread count: puts both back as they were
// when the test ends.
#include "ThreadCount.hpp"

#include <cstdlib>
#include <string>

namespace rbm::test {

class SavedThreadSettings {
public:
    SavedThreadSettings() : before_(threadCount())
    {
        if (const char* value = std::getenv("OMP_NUM_THREADS")) {
            saved_ = value;
            hadValue_ = true;
        }
    }
    ~SavedThreadSettings()
    {
        if (hadValue_) setenv("OMP_NUM_THREADS", saved_.c_str(), 1);
        else unsetenv("OMP_NUM_THREADS");
        setThreadCount(before_);
    }
    SavedThreadSettings(const SavedThreadSettings&) = delete;
    SavedThreadSettings& operator=(const SavedThreadSettings&) = delete;

private:
    int before_;
    std::string saved_;
    bool hadValue_ = false;
};

} // namespace rbm::test
