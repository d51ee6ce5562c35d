// Vulkan's flips on any mesh (pixel ids or explicit positions) checked against core's, one
// iteration at a time: the shared check of test_sampled_mesh.cpp and test_position_gains.cpp.
#pragma once

#include "cost.h"
#include "image.h"
#include "mesh.h"

namespace ddt::test {

// Gains are the same fp64 formula on both sides (glsl/image/sederberg.h, glsl/image/content_cost.h); a
// device may round a division or square root differently in the last bit, far below 1e-12 on
// the gains of these tests' meshes (random values in [0, 1]; triangles at least ~0.1 px high,
// so an SCF below ~200 and terms of a gain below ~1e3 · 1e-16).
inline constexpr double kGainTolerance = 1e-12;

// The largest flip gain of any edge of `mesh`.
double largestGain(const Mesh& mesh, const CostField& field, CostFunction cost);

// Runs the Vulkan backend (validation on) from `initial` under `cost`, checking at every
// iteration that its mesh is core's replay of the previous one, that each accepted flip's gain
// is the one core computes just before that flip, and at the end that no gain is left.
void checkVulkanStepwise(const Image& values, const Mesh& initial, CostFunction cost);

}  // namespace ddt::test
