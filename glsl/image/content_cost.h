// The costs a triangulation of an image can be optimised for, and the variance weight, written
// once in the common subset of C++ and GLSL (as glsl/image/sederberg.h, which this file builds on):
// core/image/cost.cpp, core/image/flip_gains.cpp and the kernels evaluate the same formulas.
//
//   sederberg  Σ over interior edges of SCF(e)                     (Červeňanský et al. Sec. 2.1; the default)
//   variance   Σ over triangles T of area(T) · Var(z of T's 3 vertices)        (Tóth et al. Sect. 3)
//   face_scf   Σ over triangles T of area(T) · (Σ over T's 3 edges of SCF) / 3 (Tóth et al. Sect. 3)
//
// Tóth et al., "N-dimensional data-dependent reconstruction using topological changes": the
// content-weighted form Σ content · weight makes meshes with different numbers of simplices
// comparable; in 2-D every triangulation has as many edges, and the weights are what differ.
// z is the luma the SCF reads (core/image/cost.h: Rec. 601 of the stored values in [0, 1]); an image
// with alpha adds the alpha channel's cost, as for the SCF. A boundary edge's SCF is 0.
//
// Every triangle of the grid's triangulations has area exactly 1/2: its vertices are pixel
// centres, and a triangulation that uses every pixel centre leaves no lattice point inside a
// triangle or on its sides, so Pick's theorem gives area = 0 + 3/2 − 1 = 1/2. The areas are
// computed anyway (the paper's definition, and exact integers at no cost), but it follows that
// face-SCF's cost is a third of Sederberg's on these meshes, edge by edge (SCF · (1/2 + 1/2) / 3),
// and its flips are Sederberg's but for gains within a factor 3 of kFlipGainThreshold. On a
// mesh of some pixels or of explicit positions the areas differ, and so do the three costs'
// flips (glsl/image/sederberg.h's Places; how each cost scales with the triangles: kFlipGainThreshold).
#ifndef DDTUP_CONTENT_COST_H
#define DDTUP_CONTENT_COST_H

#include "sederberg.h"

#ifdef __cplusplus
namespace ddt {
#define DDT_FN inline
#define DDT_PRECISE
#else
#define DDT_FN
#define DDT_PRECISE precise
#endif

// The cost choice's values, as core/image/cost.h's CostFunction and the kernels' kCost.
const uint kCostSederberg = 0;
const uint kCostVariance = 1;
const uint kCostFaceScf = 2;

// area(T) · Var(z0, z1, z2) from twice T's area: the population variance of three values is
// Σ (z_i − mean)² / 3 = ((z0 − z1)² + (z1 − z2)² + (z2 − z0)²) / 9, and area = twice_area / 2,
// so the product is twice_area · ((z0 − z1)² + (z1 − z2)² + (z2 − z0)²) / 18.
DDT_FN double varianceShare(double twice_area, float z0, float z1, float z2) {
    DDT_PRECISE double d01 = double(z0) - double(z1);
    DDT_PRECISE double d12 = double(z1) - double(z2);
    DDT_PRECISE double d20 = double(z2) - double(z0);
    DDT_PRECISE double squares = d01 * d01 + d12 * d12 + d20 * d20;
    DDT_PRECISE double weighted = twice_area * squares;
    return weighted / 18.0;
}

// area(T) · Var of the positive triangle T = (i0, i1, i2) with values z0..z2. Like
// planeGradient it first turns T so that its smallest vertex id comes first (orientation
// kept): every listing of one triangle then sums the squares in one order, bit-identically.
DDT_FN double varianceCost(uint i0, uint i1, uint i2, float z0, float z1, float z2, Places places) {
    if (i1 < i0 && i1 < i2) {
        uint t = i0; i0 = i1; i1 = i2; i2 = t;
        float s = z0; z0 = z1; z1 = z2; z2 = s;
    } else if (i2 < i0 && i2 < i1) {
        uint t = i0; i0 = i2; i2 = i1; i1 = t;
        float s = z0; z0 = z2; z2 = z1; z1 = s;
    }
    return varianceShare(orientation(i0, i1, i2, places), z0, z1, z2);
}

// Variance's cost decrease when e flips, for one channel: a triangle's cost depends on its own
// vertices only, so only e's two triangles change, and the gain reads e's record alone (ROI:
// the 1-region, see core/image/mesh.h). The caller checks flipIsConvex first.
//   before: triangles (a, b, l) and (b, a, r)   after: (r, b, l) and (l, a, r)
DDT_FN double varianceGain(FlipStencil s, StencilValues z, Places places) {
    DDT_PRECISE double before = varianceCost(s.a, s.b, s.l, z.a, z.b, z.l, places) +
                                varianceCost(s.b, s.a, s.r, z.b, z.a, z.r, places);
    DDT_PRECISE double after = varianceCost(s.r, s.b, s.l, z.r, z.b, z.l, places) +
                               varianceCost(s.l, s.a, s.r, z.l, z.a, z.r, places);
    return before - after;
}

// The gain of `cost` (kCost…) for one channel. Variance reads only a, b, l, r of the stencil.
DDT_FN double costFlipGain(uint cost, FlipStencil s, StencilValues z, Places places) {
    if (cost == kCostVariance) return varianceGain(s, z, places);
    return scfFlipGain(s, z, places, cost == kCostFaceScf);
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#undef DDT_PRECISE
#endif
