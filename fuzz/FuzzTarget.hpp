#pragma once
// The libFuzzer side of a fuzz target: runs one entry function of FuzzEntryPoints.hpp on the
// input and treats rbm::InputError as the expected outcome of bad input. Any other exception
// escapes, std::terminate aborts, and libFuzzer reports the input as a crash.

#include "FuzzEntryPoints.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include <unistd.h>

namespace rbm::fuzz {

template <class EntryFunction>
int runFuzzInput(EntryFunction entry, const std::uint8_t* data, std::size_t size)
{
    try {
        entry(std::string_view(reinterpret_cast<const char*>(data), size));
    } catch (const InputError&) {
    }
    return 0;
}

// Once per process: forget FOAM_CASE, which would point `<case>` and $FOAM_CASE at a real
// case. The working folder stays (libFuzzer resolves corpus and artifact paths against it);
// the readers only ever see absolute paths inside the sandbox.
inline int initializeFuzzTarget()
{
    ::unsetenv("FOAM_CASE");
    ::unsetenv("FOAM_CASESRC");
    (void)detail::Sandbox::root();
    return 0;
}

} // namespace rbm::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    return rbm::fuzz::initializeFuzzTarget();
}
