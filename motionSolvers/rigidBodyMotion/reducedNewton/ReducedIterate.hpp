#pragma once
// A point of the reduced Newton iteration: the displacements, their best-fit rotations, and
// the reduced energy and its projected gradient there (ReducedEnergy.hpp).

#include "RbmEnergy.hpp"

#include <vector>

namespace rbm::motion {

struct ReducedIterate {
    std::vector<Vector3> displacement;  // u, one per node
    std::vector<Matrix3> rotations;     // R*(u), one per node
    double energy = 0.0;                // Ẽ(u)
    std::vector<double> gradient;       // P∇Ẽ(u), compact
    double gradientNorm = 0.0;          // ‖P∇Ẽ(u)‖
};

} // namespace rbm::motion
