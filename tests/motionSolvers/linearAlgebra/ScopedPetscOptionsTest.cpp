// Tests of ScopedPetscOptions: a solver's options live in PETSc's database only in its scope,
// and never replace what the command line set.
#include "ScopedPetscOptions.hpp"

#include "PetscTestEnvironment.hpp"

#include <gtest/gtest.h>

namespace rbm::motion {
namespace {

std::string valueOf(const char* name)
{
    char value[64] = "";
    PetscBool set = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsGetString(nullptr, nullptr, name, value, sizeof value, &set));
    return set ? value : "<unset>";
}

TEST(ScopedPetscOptions, OptionsLiveInTheScopeOnlyAndTheCommandLineWins)
{
    RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, "-rbm_test_given", "commandLine"));
    {
        const ScopedPetscOptions scoped({{"-rbm_test_scoped", "cg"}, {"-rbm_test_given", "dictionary"}});
        EXPECT_EQ(valueOf("-rbm_test_scoped"), "cg");
        EXPECT_EQ(valueOf("-rbm_test_given"), "commandLine");
    }
    EXPECT_EQ(valueOf("-rbm_test_scoped"), "<unset>");
    EXPECT_EQ(valueOf("-rbm_test_given"), "commandLine");
    RBM_CHECK_PETSC(PetscOptionsClearValue(nullptr, "-rbm_test_given"));
}

} // namespace
} // namespace rbm::motion
