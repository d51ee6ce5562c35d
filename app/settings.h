// Everything the command line can set, filled by parseCommandLine and validated before any
// work starts.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ddt {

enum class ProgressMode { Auto, Bar, Json, None };
enum class Verbosity { Quiet, Normal, Verbose };

struct Settings {
    // Where the images come from and go to: `inputs` and one output file (single form), or
    // `inputs` / `input_folder` and an `output_folder`.
    std::vector<std::string> inputs;
    std::string output;         // single form: the output file ("-": standard output)
    std::string input_folder;   // -i
    std::string output_folder;  // -o
    bool recursive = false;     // -r
    std::string format;         // -f: output extension without the dot; "" = the input's
    int quality = 95;           // lossy formats
    std::string depth;          // 8, 16, half, float; "" = the input's
    bool skip_existing = false;
    std::string mesh;          // --mesh: single form, a file (.ply, .obj); batch forms, a format; "" = none
    double mesh_height = 0.0;  // --mesh-height: z = luma × this, in output pixels; 0 = flat
    double simplify = 0.0;     // --simplify: the fraction of the vertices kept, in (0, 1]; 0 = no simplification
    double max_error = 0.0;    // --max-error: the largest collapse error, RMS in 8-bit levels; 0 = none

    bool simplifies() const { return simplify > 0.0 || max_error > 0.0; }
    std::string mask;          // --mask: the image whose non-black pixels mark the input's known ones; "" = all known
    std::string mask_folder;   // --mask-dir: batches; each input's mask is the image of the same name in it
    bool fallsBack() const { return fallback.empty() ? reconstruct == "consistent" : fallback == "lanczos3"; }
    bool masked() const { return !mask.empty() || !mask_folder.empty(); }
    // --frame WxH: the frame of point-file inputs (core/delaunay/point_mesh.h); 0 = the points' own
    uint32_t frame_width = 0, frame_height = 0;

    double scale = 0.0;       // 0: not given
    // Volumes only (core/volume/): -s FX,FY,FZ, a factor per axis; all 0 when -s gave one factor.
    std::array<double, 3> axis_scales{};
    std::string cost;    // --cost: core/image/cost.h's names; "" = sederberg for images, variance for volumes (core/volume/tet_cost.h)
    std::string slices;  // --slices DIR: PNG slices through the middle of each output volume; "" = none
    bool stack = false;  // --stack: the input is a volume of 2-D slices (core/io/volume_stack.h)
    // The options given that mean nothing for volumes, as the user spelled them (--mesh, ...):
    // a volume input is refused with them.
    std::vector<std::string> image_only_options;
    uint32_t width = 0;       // 0: not given
    uint32_t height = 0;      // 0: not given
    uint32_t tile = 0;        // tile side in input pixels; 0 = automatic
    std::string backend = "auto";  // "auto", "vulkan" or "cpu" (app/backend_factory.h)
    unsigned threads = 0;          // CPU threads for the whole process; 0 = the processors it may use
    uint64_t memory = 0;           // --memory: host bytes the run may hold; 0 = half the machine's memory
    std::string variant;       // flip rule of the Vulkan backend; "" = the default
    std::string reconstruct = "consistent";  // the surface: "consistent" or "plain" (core/image/reconstruct.h)
    std::string assume = "auto";  // the downscale filter the consistent surface assumes (core/image/assumed_kernel.h)
    // lanczos3: blend towards a convolution where contrast is low (core/image/convolution_fallback.h);
    // "" (not given): lanczos3 with the consistent surface, none with the plain one, the paper's.
    std::string fallback;
    int device = -1;           // Vulkan device index; -1 = choose
    // Where masks' and point files' samples are triangulated: "auto" (the device on a GPU, the
    // host on a CPU device or the CPU backend), "cpu" or "device" (app/backend_factory.h)
    std::string delaunay = "auto";
    bool active_set = true;    // Vulkan: re-test only edges a flip may have changed
    bool list_devices = false;
    bool stats = false;
    ProgressMode progress = ProgressMode::Auto;
    Verbosity verbosity = Verbosity::Normal;

    bool quiet() const { return verbosity == Verbosity::Quiet; }
    // One input to one named output file, the form `ddtup IN OUT`.
    bool singleForm() const { return output_folder.empty(); }
};

}  // namespace ddt
