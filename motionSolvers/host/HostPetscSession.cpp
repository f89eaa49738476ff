#include "HostPetscSession.hpp"

#include <mutex>

namespace rbm::host {

std::shared_ptr<motion::PetscSession> sharedPetscSession()
{
    static std::mutex mutex;
    static std::weak_ptr<motion::PetscSession> current;
    const std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<motion::PetscSession> session = current.lock();
    if (!session) {
        session = std::make_shared<motion::PetscSession>();
        current = session;
    }
    return session;
}

} // namespace rbm::host
