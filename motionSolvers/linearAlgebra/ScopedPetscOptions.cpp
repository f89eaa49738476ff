#include "ScopedPetscOptions.hpp"

#include "PetscSupport.hpp"

namespace rbm::motion {

ScopedPetscOptions::ScopedPetscOptions(const std::vector<std::pair<std::string, std::string>>& options)
{
    for (const auto& [name, value] : options) {
        PetscBool set = PETSC_FALSE;
        RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
        if (set) continue;
        RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
        inserted_.push_back(name);
    }
}

ScopedPetscOptions::~ScopedPetscOptions()
{
    // A destructor does not throw: a failure to clear leaves an option that only this
    // solver's own prefix reads.
    for (const std::string& name : inserted_) (void)PetscOptionsClearValue(nullptr, name.c_str());
}

} // namespace rbm::motion
