// Upscaling an image of any size on a backend of limited memory: untiled when the input
// fits, else in tiles (core/image/tiling.h) whose seams do not show; when the device runs out of
// memory anyway, the tile side is halved and the failed strip redone, so the caller gets
// every output row once, in order, or an error, never a partial image. A backend with twins
// (the CPU) processes a strip's tiles in parallel, one per thread, each within its share of
// the memory; the output is the same bytes as with serial tiles.
#pragma once

#include <cstdint>
#include <functional>

#include "backend.h"
#include "known_samples.h"
#include "output_rows.h"
#include "packed_image.h"
#include "stitched_mesh.h"

namespace ddt {

// Input pixels a tile's crop reaches beyond its core on each side. A flip depends on a
// neighbourhood a few pixels wide, and Lawson's flips cascade a little further; the mesh a
// crop converges to differs from the untiled one only near the crop's border. Measured
// (test/image/test_tiling.cpp: 300×200 photo, edge and noise images, ×2, 64-pixel tiles, both
// backends): overlap 4 leaves differences up to 142/255 on 0.03 % of samples, overlap 8
// and more gives outputs equal to the untiled ones, bit for bit. 16 doubles that margin for
// (1 + 32 / side)² more work: 3 % for 2048-pixel tiles. The consistent reconstruction and
// flat drawings reach further: on three photographs ×2 in 256-pixel tiles (`--depth float`,
// against one piece) tiles differ by at most 0.53/255 with an overlap of 8, 0.013/255 with 12
// and 0.0001/255 with 16, but bench/tiling_check.sh 256 finds the bundled drawings' seams at
// up to 20 levels with 12 (rocket_clipart, 0.08 % of its samples) against 9 with 16 (0.04 %).
const uint32_t kDefaultOverlap = 16;
// Smaller tiles would be mostly overlap; below this the device is hopeless.
const uint32_t kMinTileSide = 64;
// Where tiles run side by side (the CPU backend: one serial optimisation per thread), an
// image whose longer side exceeds this goes in tiles of this side even where it would fit
// in one piece: in one piece every thread but one waits through the flips, and the sweeps
// slow down per pixel as a mesh outgrows the caches. A 512² PNG to ×8 took 0.51 s and
// 120 MiB in one piece, 0.41 s and 80 MiB in 256-pixel tiles (bench/README.md). Automatic
// tiles come in a multiple of the threads a strip (stripColumns), so that no thread waits
// through a strip's last tile.
const uint32_t kParallelTileSide = 256;

// Where upscaleRows is: about to prepare and optimise tile k of n, to reconstruct its
// surface, or to render it.
enum class TilePhase { Optimize, Reconstruct, Render };
struct TileStep {
    uint32_t tile = 0;
    uint32_t tiles = 1;
    TilePhase phase = TilePhase::Optimize;
};
using TileStepCallback = std::function<void(const TileStep&)>;

struct TileOptions {
    uint32_t tile = 0;  // tile side in input pixels; 0 = automatic: tiles only when the input does not fit
    uint32_t overlap = kDefaultOverlap;  // 0 counts as 1
    bool reconstruct = false;            // each tile's surface: consistent (core/image/reconstruct.h) or plain
    AssumedKernel kernel = AssumedKernel::mixed;  // the consistent surface's assumed downscale filter
    bool fallback = false;               // blend towards Lanczos3 where contrast is low (core/image/convolution_fallback.h)
    StitchedMesh* mesh = nullptr;        // if set, gets every tile's optimised mesh (of the strips that succeed)
    // A mask's known pixels or a point file's points (their gaps measured): each tile then
    // triangulates its crop's samples, the crop grown to hold the gaps near it
    // (app/delaunay/sampled_tile.h); the plain surface, no fallback, no mesh file. A point
    // file's `input` is a header of its frame, without pixels.
    const KnownSamples* known = nullptr;
    // 8 or 16 where the rows' floats go to a writer that makes them codes of those bits and
    // nothing else (ImageWriter::codeBits): a strip rendered at once is kept as codes
    // (app/strip_rows.h). 0: as floats.
    uint32_t code_bits = 0;
};

// The tile side automatic tiling picks for a width × height input with `channels` channels
// (and the consistent surface, with `reconstruction`): 0 when it fits the backend untiled,
// else the largest multiple of 256 (or 128, then 64) whose crops fit; either with 1/8 of the
// backend's memory to spare.
uint32_t automaticTileSide(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels,
                           uint32_t overlap, bool reconstruction);

// "" if a width × height job that cannot be tiled (a mask's, a simplification's), holding
// `extra` bytes beside the backend's, fits the backend's memoryLimit with 1/8 to spare; else
// the reason, for "W×H: …".
std::string untiledMemoryProblem(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels,
                                 uint64_t extra = 0);

// Upscales `input` to `out` and hands the output rows to `sink` in order, each row exactly
// once, out.width × channels floats per row; the tiles' crops are made floats as they go
// (core/image/packed_image.h), and an input decoded as its rows are needed holds only a
// strip's crops' rows. `on_step` is
// called before each tile is optimised and before it is rendered (the tile count may grow
// after a retry with smaller tiles); with tiles in parallel, from their threads in turn.
// Returns the optimisation statistics summed over the tiles (overlaps counted in each tile).
// Throws UserError when even kMinTileSide tiles do not fit the device.
OptimizeStats upscaleRows(Backend& backend, PackedImage& input, OutputSize out, const TileOptions& options,
                          const std::function<void(OutputRows&& rows)>& sink,
                          const TileStepCallback& on_step = {});

}  // namespace ddt
