// One image's way through a run, in the three stages the pipeline overlaps: read (decode, and
// open the output so that a bad output fails before the long part), process (triangulate,
// optimize, render) and write (encode, then rename into place). Process and write run at the
// same time on one image: rendered bands go to the encoder through a BandStream.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assumed_kernel.h"
#include "backend.h"
#include "band_stream.h"
#include "batch_plan.h"
#include "memory_budget.h"
#include "reporter.h"
#include "settings.h"
#include "image_file.h"
#include "indexed_mesh.h"

namespace ddt {

// What --stats prints. Building the mesh and uploading it count as optimizing here, not as
// init: tiled images build one mesh per tile, between the optimizations.
struct StageTimes {
    double init_s = 0.0;   // read the header and decode (an input decoded as its tiles need it: in comp_s)
    double comp_s = 0.0;   // build the mesh, upload, optimize (per tile when tiled)
    double reconstruct_s = 0.0;  // the consistent reconstruction (per tile when tiled)
    double final_s = 0.0;  // render + write (the paper's time-final saved the mesh instead)
};

struct JobReport {
    OptimizeStats stats;
    std::optional<AssumedKernel> assumed;  // what the consistent surface assumed, when it was made
    std::optional<ParallelSimplifyStats> simplify;  // with --simplify or --max-error
    std::optional<bool> delaunay_on_device;  // a mask's or point file's: where its samples were triangulated
    StageTimes times;
    OutputSize out;
};

// Documented limit on output pixels: beyond it a run would take hours and files get unwieldy.
inline constexpr uint64_t kMaxOutputPixels = uint64_t(1) << 32;

class ImageJob {
public:
    ImageJob(size_t index, const ImageTask& task, const Settings& settings, Reporter& reporter);
    ~ImageJob();

    // Each throws UserError ("PATH: reason") when the image fails. open() reads the header
    // and opens the output, decode() the pixels, or on the plain path readies a JPEG's or
    // PNG's rows to be decoded as the tiles reach them (core/image/row_decoder.h).
    void open();
    void decode();
    // Before process(): the stream its rendered bands go through, within `budget`.
    void streamOutput(MemoryBudget& budget);
    // Renders into the stream; on failure the stream is abandoned. Throws OutputClosed when the
    // writer gave up (it reported why).
    void process(Backend& backend);
    // Encodes the stream's bands as they come and commits the file; false, without a word,
    // when process() abandoned the image (it reported why).
    bool write();

    // Host memory the job holds at most from decode() to its end (after open()).
    uint64_t hostMemory() const;
    // The lease on the pipeline's memory budget, ended with the job.
    void holdMemory(MemoryBudget::Lease lease) { memory_ = std::move(lease); }

    size_t index() const { return index_; }
    const ImageTask& task() const { return task_; }
    const JobReport& report() const { return report_; }

private:
    WriteOptions writeOptions() const;
    // The filter --assume names, or for auto the one the input's file format suggests.
    AssumedKernel assumedKernel() const;
    void render(Backend& backend);
    // Writes the task's mesh file from the stitched triangles of the optimised mesh.
    Image openPoints();
    // A mask's or a point file's samples triangulated where the backend does it (--delaunay):
    // in the processing stage, which owns the device, not in the reader's.
    void triangulateSamples(Backend& backend);
    // The tile side of a mask's or a point file's tiles (--tile, else automatic), 0 when it is
    // done in one piece: a mask that fits the backend's working memory, points whose mesh and
    // output fit --memory, or --mesh or a simplification wants the whole triangulation.
    uint32_t sampledTileSide(const Backend& backend) const;
    // A point file's samples kept for tiles (core/delaunay/known_samples.h), the input a header
    // of the frame (or the frame's pixels for points on pixel centres, as a mask's).
    void keepPointsForTiles();
    // The whole input as floats, for the paths that take it whole (samples, simplification,
    // the mesh file's colours); an input kept as codes is unpacked from then on.
    const Image& inputFloats();
    // Checks that the tiles' meshes join, then writes them as --mesh asks.
    void writeTiledMesh(std::vector<uint32_t> triangles, std::vector<Position> positions);
    // Writes --mesh's file: `indexed` over `frame` (input pixels), with `coverage` appended to
    // the comment that states the conventions.
    void writeMesh(const IndexedMesh& indexed, OutputSize frame, const std::string& coverage);

    struct State;
    size_t index_;
    ImageTask task_;
    const Settings& settings_;
    Reporter& reporter_;
    JobReport report_;
    std::unique_ptr<State> state_;
    MemoryBudget::Lease memory_;
};

}  // namespace ddt
