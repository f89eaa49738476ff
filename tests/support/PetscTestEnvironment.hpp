#pragma once
// Initialises PETSc once per test program (every CTest entry pays PETSc's start-up once):
// including this header registers the environment, once per program. The solvers of a test
// (the host solvers too) share that session instead of finalising PETSc, and the MPI it
// started, when the first of them goes.

#include "PetscSupport.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace rbm::test {

class PetscTestEnvironment : public ::testing::Environment {
public:
    void SetUp() override { session_ = std::make_unique<motion::PetscSession>(); }
    void TearDown() override { session_.reset(); }

private:
    std::unique_ptr<motion::PetscSession> session_;
};

// The registration: an inline variable, so one per program whichever files include this.
inline ::testing::Environment* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new PetscTestEnvironment);

} // namespace rbm::test
