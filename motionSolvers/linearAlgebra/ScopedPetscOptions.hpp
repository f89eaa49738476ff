#pragma once
// PETSc options of a solver's coefficient dictionary (`petscOptions "..."`), present in
// PETSc's options database only while that solver builds or runs its PETSc objects, so that
// two solvers in one program do not see each other's options. Options already in the
// database (the program's command line, PETSC_OPTIONS) are left alone: the command line wins.

#include <string>
#include <utility>
#include <vector>

namespace rbm::motion {

class ScopedPetscOptions {
public:
    // (name, value) pairs, names with their leading '-'; an empty value sets a flag.
    explicit ScopedPetscOptions(const std::vector<std::pair<std::string, std::string>>& options);
    ~ScopedPetscOptions();
    ScopedPetscOptions(const ScopedPetscOptions&) = delete;
    ScopedPetscOptions& operator=(const ScopedPetscOptions&) = delete;

private:
    std::vector<std::string> inserted_;
};

} // namespace rbm::motion
