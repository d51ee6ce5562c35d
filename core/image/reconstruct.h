// Consistent reconstruction on the optimised mesh (`--reconstruct consistent`, the default;
// `--reconstruct plain` renders the paper's surface).
//
// Plain DDT takes the input's pixel values as point samples of a surface that is linear on
// each triangle. But a pixel of a downscaled picture or of a camera is an average over its
// footprint, so that surface, degraded again, does not give the input back, and a linear
// patch is a poor interpolant between samples. The consistent reconstruction keeps the
// optimised triangulation and changes the surface on it:
// - The surface is quadratic on each triangle (core/image/render.h): the vertex values v, linear,
//   plus one bubble b_e per edge, 4·λp·λq·b_e on the edge's two triangles. Everything stays on
//   the mesh: a vertex value reaches only the triangles around its vertex and a bubble only
//   the two triangles of its edge, so no correction crosses the long edges DDT found.
// - Bubbles start as the midpoint of a cubic along their edge's line, (−y(2p−q) + 9 y(p) +
//   9 y(q) − y(2q−p)) / 16 minus the linear midpoint (points clamped into the image). Vertex
//   values start as the input's.
// - Then kReconstructIterations steps of SART (simultaneous algebraic reconstruction) make the
//   degraded surface D(S) approach the input y: with the residual r = y − D(S), every unknown
//   u (a vertex value or a bubble) moves by ω·⟨φ_u, Dᵀr⟩ / ⟨φ_u, Dᵀ1⟩, φ_u its basis function,
//   ω = kRelaxation. Measured on the bench's 20 images: 3 steps at ω = 1.5 score as 5 steps
//   at ω = 1 (−0.01 to +0.09 dB, protocols A and B, ×2 to ×8) for 40 % less work.
// - Regularisation: few steps (early stopping damps the frequencies D nearly removes, where
//   noise and JPEG artefacts live), and a residual counts only beyond half a quantisation step
//   of the input's sample type (1/510 for 8 bits, 0 for float): within it the surface already
//   agrees with the stored value, and chasing the rest would sharpen rounding noise.
// - Bounded overshoot: after every step each vertex value is clamped to the range of the
//   input's 3 × 3 pixels around it (the stated margin is none), to [0, 1] for integer sample
//   types, and premultiplied colour to at most its alpha. The renderer clamps each quadratic
//   sample to its triangle's vertex range. Where consistency would need more (a sharp step
//   under area averaging), the bound wins. Measured on the bench (protocol B, ×2 to ×8): a
//   margin of 25 % of the local range overshot the 4 × 4 input pixels around each sample by
//   0.35–0.83 levels on average, more than Lanczos3's 0.13–0.25, and scored 0.05–0.17 dB
//   lower than no margin (0.01–0.03 levels).
//
// The degradation model D, in input-pixel units: the assumed downscale filter K
// (core/image/assumed_kernel.h, `--assume`; by default `mixed`, below) on the supersampling.
//   D(S)(x) = Σ_d g(d) S(x + d), d on a fixed kSupersampling × kSupersampling grid per input
//   pixel (offsets −1/3, 0, +1/3), g(d) = K(d / w) separable, truncated at K's support,
//   normalised, with a width w per axis; the samples near the border are clamped into the
//   image. At s = 1, w = 0: D is the identity, the residual is zero and the output is the input.
// - The footprint is a Gaussian of standard deviation kFootprintSigma = 0.4 input
//   pixels as s → ∞: a box of one pixel (area averaging) has σ = 0.29, repeated bilinear
//   halvings about 0.45, and a camera's pixel aperture with its optics lies between. Its
//   w(s) = √(1 − 1/s²) is the spread of s point samples spaced 1/s across one input pixel,
//   which is what averaging the s output pixels over an input pixel means; it grows
//   continuously from 0 (0.87 at ×2, 0.97 at ×4).
// - A named resize filter (box, bicubic, lanczos3) has w = 1 for every s > 1: a resize to 1/s
//   stretches the filter to the small image's pixels, whatever s. (The footprint's w(s) on
//   them scored 0.1–0.4 dB lower at ×2 on the outside photographs, bench/README.md.)
// - `mixed`, the default, is for an input whose downscale is unknown: its taps are
//   kMixedFootprintShare of the footprint's at w(s) and the rest of bicubic's at w = 1, each
//   normalised, centred on one another. One reconstruction under this compromise scored as
//   well on held-out photographs as averaging the surfaces of the two assumptions, which
//   costs two (bench/README.md, "Mixed assumption").
// - The surface is evaluated on the fixed supersampling whatever the output size: the final
//   render at the requested size is the only step whose cost grows with the scale. On the
//   grid's mesh each supersample is a vertex's, an edge's third or a triangle's centroid
//   (core/image/supersample_lattice.h), so the solver's passes go element by element.
#pragma once

#include <cstdint>
#include <vector>

#include "assumed_kernel.h"
#include "image.h"
#include "mesh.h"
#include "uninitialised_vector.h"

namespace ddt {

constexpr uint32_t kReconstructIterations = 3;
constexpr float kRelaxation = 1.5f;           // SART's relaxation, in (0, 2)
constexpr uint32_t kSupersampling = 3;        // odd, so each pixel's centre is a sample

// The degradation per axis for realised factors sx, sy (output / input size).
struct DegradationModel {
    AssumedKernel kernel = AssumedKernel::mixed;
    double width_x = 0.0, width_y = 0.0;  // w per axis, a fraction of K's full width; 0: no blur

    bool identity() const { return width_x == 0.0 && width_y == 0.0; }
};
DegradationModel degradationFor(double scale_x, double scale_y, AssumedKernel kernel = AssumedKernel::mixed);

// Whether stored values of the sample type are limited to [0, 1] (8 and 16 bits), so that the
// reconstruction's values are too.
bool boundedToUnit(SampleType type);

// Half a quantisation step of the sample type: how far a stored value may be from the value it
// stands for (float samples are taken as exact). Residuals count only beyond it.
float quantisationTolerance(SampleType type);

// The model's taps along one axis on the supersampling: weight of offset t / kSupersampling
// for t in [−radius, radius], normalised; {1} for width 0.
std::vector<float> degradationTaps(AssumedKernel kernel, double width);

// A quadratic surface on a mesh: vertex values and one bubble per edge (render.h).
struct Surface {
    Image values;                        // the vertex values, like the input image
    UninitialisedVector<float> bubbles;  // edgeCount() × channels
};

// The starting surface: the input's values and the cubic-midpoint bubbles.
Surface initialSurface(const Mesh& mesh, const Image& input);

// The consistent surface for `mesh`, the grid's (no explicit positions), optimised on `input`,
// under `model`.
Surface reconstructSurface(const Mesh& mesh, const Image& input, const DegradationModel& model,
                           uint32_t iterations = kReconstructIterations);
// The same, consuming the mesh (its edge records are taken over and the rest freed before the
// solver's arrays are made), with its triangles as a caller that renders afterwards already
// has them (MeshRenderer::triangles()).
Surface reconstructSurface(Mesh&& mesh, const Image& input, const DegradationModel& model,
                           const std::vector<Triangle>& triangles, uint32_t iterations = kReconstructIterations);

}  // namespace ddt
