// The kept vertices' colours of a simplified mesh, fitted to the picture: the colours whose
// linear surface comes closest, in least squares, to the picture's pixels at their centres.
//
// The quadrics give each vertex the colour that fits the planes it absorbed, one vertex at a
// time; neighbours do not see each other's choice. The surface at a pixel mixes up to three
// vertices, so fitting them together is better: measured at 10 % of the vertices (five
// photographs ×4 from quarter size, PSNR against the original), 23.98 dB with the quadrics'
// colours, 24.25 dB fitted (+0.09 to +0.41 per photograph).
//
// The fit minimises Σ_pixels |surface(centre) − pixel|² + μ Σ_vertices |colour − start|²
// per channel, the start being the quadric colour: μ = 1e-3 (a pixel weighs λ² ≤ 1, a vertex
// has tens) only holds a vertex no pixel centre sees, which thin triangles can leave. Conjugate
// gradients from the start, a fixed sum order (deterministic), until the residual is 1e-6 of
// the right-hand side (a relative accuracy far below an 8-bit level; about 10 iterations on
// the photographs, none where the start fits already, as on an unsimplified mesh). Colours of integer sample types are then
// clamped to [0, 1], premultiplied ones to at most their alpha. Vertices on a locked side
// (Mesh::locked_sides) keep their starting colours: the fit solves for the others only.
#pragma once

#include <vector>

#include "image.h"
#include "mesh.h"

namespace ddt {

// A simplified triangulation of samples (MeshHull::convex: a mask's known pixels, a point
// file's points) is fitted to its samples instead of to every pixel centre: the unknown pixels
// have no values, and points need not lie on centres. A sample is a vertex of the mesh the
// simplification started from: its id (its value is the picture's entry there) and its place.
struct KnownSample {
    uint32_t vertex;
    Position place;
};
// The vertices `mesh` uses, where they are now.
std::vector<KnownSample> knownSamplesOf(const Mesh& mesh);

// `colours` holds each vertex's starting colour (per vertex id, as the picture's pixels are
// laid out) on entry and the fitted one on return; `picture` is the picture the mesh was made
// from (the same size). `samples`: where the picture is known (knownSamplesOf the mesh before
// simplification, every one inside `mesh`'s hull), or empty: at every pixel centre.
void fitColours(const Mesh& mesh, const Image& picture, Image& colours, const std::vector<KnownSample>& samples = {});

}  // namespace ddt
