#pragma once
// Initialises PETSc once per test program (every CTest entry pays PETSc's start-up once).
// Register it from the test file:
//   static auto* const petscEnvironment = ::testing::AddGlobalTestEnvironment(new rbm::test::PetscTestEnvironment);

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

} // namespace rbm::test
