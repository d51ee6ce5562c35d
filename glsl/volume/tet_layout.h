// Constants, bindings, the control block and the push constants of the tetrahedral flip kernels
// (glsl/volume/), shared by them, the host side (compute/volume/) and core's parallel rule
// (core/volume/tet_parallel.h, for tetTieWord). Written in the common subset of C++ and GLSL
// (GLSL includes it after GL_EXT_shader_explicit_arithmetic_types_int64).
//
// Every per-slot and per-vertex array is a storage texel buffer, for glsl/layout.h's reasons
// (limited in elements, not bytes: no 128 MiB binding limit; vector gathers on lavapipe).
// Doubles travel as their two 32-bit halves (rg32ui).
#ifndef DDTUP_TET_LAYOUT_H
#define DDTUP_TET_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#else
#define DDT_FN
#endif

// The low word of a candidate's selection key (core/volume/tet_parallel.h): a bijection of its
// owner's slot, so keys stay unique and equal gains are decided in a mixed order rather than
// along the grid's rows. Wellons' "lowbias32" (his hash-prospector), each step invertible.
DDT_FN uint tetTieWord(uint owner) {
    uint x = owner;
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Invocations per workgroup. One invocation handles one item (list entry, candidate, slot), so
// its loop trips stay small against llvmpipe's limit (glsl/layout.h: every loop of an
// invocation together ends silently after 65 535 iterations): the candidates' 16 attempts, each
// with its small loops unrolled (or, if a compiler kept them, ~1 000 trips: ~16 000 in all);
// the plan's sum over the scan blocks, capacity / 32 768 (4 096 at lavapipe's 2^27 texels);
// the scan's 16 words and 64 partial sums. The work of a large list goes into more
// workgroups, in a second dimension beyond kTetMaxGroups, never into longer loops.
const uint kTetGroupSize = 64u;
// Workgroups per dimension of an indirect dispatch (Vulkan's guaranteed minimum); larger counts
// go to a second dimension (tetArgs).
const uint kTetMaxGroups = 65535u;
// A candidate names its owner's slot in the low 28 bits and its site above them, so slots stay
// below 2^28 (texel buffers hold at most 2^27 elements on lavapipe anyway).
const uint kTetSiteShift = 28u;
const uint kTetMaxSlots = 1u << kTetSiteShift;
// Sites (tet_flips.h's order): faces 0–3 (2–3), edges kTetSiteEdge + k of bestFlipAt's k-th
// edge (3–2, 2–2, the 4–4 to diagonal 0), kTetSiteDiagonal + k (the 4–4 to diagonal 1).
const uint kTetSiteEdge = 4u;
const uint kTetSiteDiagonal = 10u;
// Set in a candidate's key word (a positive double's high word, whose sign bit is 0) once it is
// accepted.
const uint kTetAccepted = 0x80000000u;
// The allocation's ranks: bit (owner % 32) of mask word 2 (owner / 32) + kind, kind 0 for the
// accepted 2–3 flips, 1 for the 3–2 flips; prefix sums over blocks of kTetScanWords words.
const uint kTetScanWords = 1024u;  // 64 invocations × 16 words: 32768 slots a block
const uint kTetScanWordsPerInvocation = kTetScanWords / kTetGroupSize;

// Bits of a slot's state word: its tet's four values are equal; listed in the active list;
// listed in the evaluation list.
const uint kTetStateFlat = 1u;
const uint kTetStateActive = 2u;
const uint kTetStateEval = 4u;

// Bindings (set 0).
const uint kTetBindingVertices = 0u;    // rgba32ui per slot (TetMesh::vertices)
const uint kTetBindingNeighbours = 1u;  // rgba32ui per slot
const uint kTetBindingValues = 2u;      // rg32ui per vertex: the normalized value (double)
// rg32ui: last round's unaccepted candidates carried over (as candidates). (Binding 3 held the
// contents once; they are recomputed now, tet_common.glsl's contentOf.)
const uint kTetBindingCarried = 3u;
// rg32ui: TetCosts::cost (double). face_scf: per slot, the cache. variance: the costs are
// recomputed (tet_plan.glsl's finishPlan), so this holds only kTetStepTotals' chunk of them.
const uint kTetBindingCost = 4u;
const uint kTetBindingGradient = 5u;    // rg32ui, 3 per slot: TetCosts::gradient (face_scf)
const uint kTetBindingState = 6u;       // r32ui per slot: kTetState… bits
const uint kTetBindingClaimHigh = 7u;   // r32ui per slot: the largest key's high word claiming it
const uint kTetBindingClaimLow = 8u;    // r32ui per slot: the largest tie word among those
const uint kTetBindingFreeSlots = 9u;   // r32ui: TetMesh::free_slots, control.free_count of them
const uint kTetBindingFreed = 10u;      // r32ui: the round's freed slots by 3–2 rank
const uint kTetBindingActive = 11u;     // r32ui: the active list (new tets first, then neighbours)
const uint kTetBindingEvaluate = 12u;   // r32ui: the tets to evaluate (in no order)
const uint kTetBindingCandidates = 13u; // rg32ui: owner | site << kTetSiteShift, key's high word
const uint kTetBindingMasks = 14u;      // r32ui: 2 words per 32 slots (see kTetScanWords)
const uint kTetBindingWordPrefix = 15u; // rg32ui per mask word: the ranks before it in its block
const uint kTetBindingBlocks = 16u;     // rgba32ui per block: totals (2–3, 3–2), then prefixes
const uint kTetBindingControl = 17u;    // storage buffer: TetControl
const uint kTetBindingArgs = 18u;       // storage buffer: kTetStepCount indirect arguments
// rgba32i per vertex: its index coordinates (x, y, z, 0). Decoding an id takes two divisions and
// two remainders, which llvmpipe does lane by lane (no vector integer division on x86): computed
// per vertex of every new tet, they took most of the candidates' time.
const uint kTetBindingPositions = 19u;
const uint kTetBindingCount = 20u;

// The steps of a round, in order; each is one planned indirect dispatch (tet_plan.comp).
const uint kTetStepMark = 0u;        // tet_mark: the owners of the active tets' sites → evaluation list
const uint kTetStepCandidates = 1u;  // tet_candidates: the best owned flips, and the carried candidates
// tet_select: the candidates' read sets' claims set to 0. Before the claims rather than after
// them, so that the claims array is never zeroed whole: only the claims of read sets are read,
// and on a device whose memory is host memory (lavapipe) a whole zeroed array is resident.
const uint kTetStepClear = 2u;
const uint kTetStepClaimHigh = 3u;   // tet_select: claims, high words (and the evaluation bits cleared)
const uint kTetStepClaimLow = 4u;    // tet_select: claims, tie words
const uint kTetStepCheck = 5u;       // tet_select: accepted ones, their mask bits
const uint kTetStepTake = 6u;        // tet_select: the accepted ones' read sets marked taken
const uint kTetStepJudge = 7u;       // tet_select: the others evaluated anew or carried over
const uint kTetStepScan = 8u;        // tet_scan: the masks' prefix sums within blocks
const uint kTetStepApply = 9u;       // tet_apply: the flips
const uint kTetStepRefresh = 10u;    // tet_refresh: new tets' geometry, neighbours listed, freed slots pushed
const uint kTetStepCosts = 11u;      // tet_costs: the active tets' costs
const uint kTetStepUnmask = 12u;     // tet_scan: the masks back to 0; the round ends
const uint kTetStepCount = 13u;
// tet_refresh and tet_costs over every slot: the first round's cache (dispatched directly).
const uint kTetStepInit = 100u;
// tet_costs, variance: the costs of slots push.first… (kTetCostChunk of them at most) into
// tet_cost[0…], for the host's totals (dispatched directly).
const uint kTetStepTotals = 101u;
const uint kTetCostChunk = 1u << 20;  // 8 MiB of costs
// claim_high of a tet in an accepted candidate's read set, after kTetStepTake (no key's high
// word: a positive double's sign bit is 0).
const uint kTetTaken = 0xffffffffu;

// control.phase.
const uint kTetPhaseRunning = 0u;
const uint kTetPhaseDone = 1u;  // a round accepted nothing, or the cap on rounds
const uint kTetPhaseGrow = 2u;  // stopped before kTetStepApply: the flips need more slots (control.need)

// Written by the kernels, read by the host after each submit.
struct TetControl {
    uint phase;
    uint next_step;        // the step the next plan dispatch of that step carries out
    uint rounds;           // rounds done, as TetParallelStats::rounds
    uint capped;
    uint slot_count;       // TetMesh::slotCount()
    uint free_count;       // entries of free_slots
    uint active_count;     // entries of the active list
    uint new_count;        // of which the first ones, the new tets (tet_apply)
    uint eval_count;       // entries of the evaluation list
    uint skipped;          // of which free slots (freed since they were listed)
    uint carry_count;      // entries of the carried list
    uint candidate_count;  // entries of the candidate list
    uint two_threes;       // the round's accepted 2–3 flips (the allocation's n23)
    uint three_twos;       // and 3–2 flips
    uint base_free;        // free_count and slot_count at the round's flips
    uint base_slots;
    uint need;             // slots the round's flips need (kTetPhaseGrow)
    uint round_flips[4];   // the round's accepted flips by FlipKind
    uint pad;
    uint64_t flips[4];     // totals by FlipKind
    uint64_t evaluated;    // TetParallelStats::evaluated
    uint64_t candidates;   // TetParallelStats::candidates
};

// Push constants of every kernel.
struct TetPush {
    uint size_x;           // vertices along x, y, z
    uint size_y;
    uint size_z;
    uint face_scf;         // 1: TetWeight::face_scf, 0: variance
    uint step;             // kTetStep…
    uint capacity;         // slots the arrays hold
    uint blocks;           // scan blocks: ceil(capacity / (32 · kTetScanWords))
    uint max_rounds;
    uint spacing_bits[6];  // the physical voxel size along x, y, z, doubles as (low, high) words
    uint content_scale_bits[2];  // sx · sy · sz / 6 (tet_cost.cpp's contentScaleOf)
    uint first;            // kTetStepTotals: the chunk's first slot
};

#ifdef __cplusplus
static_assert(sizeof(TetControl) == 136 && offsetof(TetControl, flips) == 88, "TetControl layout (std430: 64-bit totals 8-aligned)");
static_assert(sizeof(TetPush) == 17 * 4, "TetPush layout");
}  // namespace ddt
#endif
#undef DDT_FN
#endif
