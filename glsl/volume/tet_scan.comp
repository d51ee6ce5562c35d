#version 460
#extension GL_GOOGLE_include_directive : require
// The slot allocation's prefix sums (core/volume/tet_parallel.h, step (c)): the accepted 2–3
// and 3–2 flips' owner bits (masks, two words per 32 slots) counted within blocks of
// kTetScanWords words, one workgroup a block: per word, the flips before it in its block
// (word_prefix), per block its totals (blocks.xy; tet_plan.comp adds up the blocks, a few
// hundred, into blocks.zw). A flip's rank in owner order is then blocks.zw + word_prefix +
// the bits below its own in its word. push.step kTetStepUnmask zeroes the masks instead.
#include "tet_common.glsl"

shared uvec2 partial[kTetGroupSize];

uvec2 bitsAt(uint word) {
    return uvec2(bitCount(imageLoad(masks, int(2u * word)).x), bitCount(imageLoad(masks, int(2u * word + 1u)).x));
}

void main() {
    const uint lane = gl_LocalInvocationID.x;
    const uint first = gl_WorkGroupID.x * kTetScanWords + lane * kTetScanWordsPerInvocation;
    if (push.step == kTetStepUnmask) {
        for (uint k = 0u; k < 2u * kTetScanWordsPerInvocation; ++k) imageStore(masks, int(2u * first + k), uvec4(0u));
        return;
    }
    uvec2 sum = uvec2(0u);
    for (uint k = 0u; k < kTetScanWordsPerInvocation; ++k) sum += bitsAt(first + k);
    partial[lane] = sum;
    barrier();
    if (lane == 0u) {
        uvec2 running = uvec2(0u);
        for (uint l = 0u; l < kTetGroupSize; ++l) {
            const uvec2 c = partial[l];
            partial[l] = running;
            running += c;
        }
        imageStore(blocks, int(gl_WorkGroupID.x), uvec4(running, 0u, 0u));
    }
    barrier();
    uvec2 running = partial[lane];
    for (uint k = 0u; k < kTetScanWordsPerInvocation; ++k) {
        imageStore(word_prefix, int(first + k), uvec4(running, 0u, 0u));
        running += bitsAt(first + k);
    }
}
