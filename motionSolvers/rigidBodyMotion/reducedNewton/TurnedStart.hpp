#pragma once
// The cold start of the reduced Newton method where the boundary is one rigid body in a fixed
// frame: the harmonic interpolation of the body's TURN. s = K⁻¹ b(1 on the body, 0 on the fixed
// nodes), and every node moved by the body's motion scaled by s — turned by s θ about the
// body's centre and shifted by s t — instead of interpolating the displacement vectors, which
// shortens the cells between (a turned neighbourhood's chord, not its arc). Near a large turn
// its energy is far below the interpolated displacements'; the caller keeps the start of
// lower energy.

#include "LaplacianPreconditioner.hpp"
#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

// u's unknown nodes ← the turned start. From the reference positions (base empty: cold) or
// from base's displacements (a warm start without history: the body's motion since base
// turned in). False where it does not apply: sliding nodes, several ranks, K not factorised by
// rbm nor its 3D cycle, the prescribed nodes not one rigid motion, a turn near a half turn.
bool turnedHarmonicStart(const RbmProblem& problem, LaplacianPreconditioner& preconditioner,
                         std::span<const Vector3> prescribedDisplacement, std::vector<Vector3>& u,
                         std::span<const Vector3> base = {});

} // namespace rbm::motion
