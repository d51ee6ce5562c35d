// Volume files: NRRD (.nrrd, and .nhdr with its data beside it) through teem's nrrd library,
// NIfTI-1 and NIfTI-2 (.nii, .nii.gz) through niftilib. core/volume/volume.h says what a
// Volume is; this file what is read, what is kept for the output, and what is refused.
//
// Reading. Samples: unsigned and signed 8 and 16 bits, float and double (int32, uint32, 64-bit,
// complex and colour types are refused). Volume::values holds physical values: a NIfTI
// file's scl_slope and scl_inter applied (a slope of 0 means none, as the standard says).
// NaN and infinite samples are refused, after scaling: interpolation would spread them over
// their neighbours. Only plain scalar volumes are read: three axes of at least 2 voxels each,
// no time or component axis (a 4-D series, an RGB or vector NIfTI, an NRRD with a list,
// vector or colour axis are refused), within kMaxVolumeSide and kMaxVolumeVoxels.
// Geometry (Volume::index_to_world):
// - NRRD: `space directions` and `space origin`; with only `spacings`, a diagonal affine at
//   origin 0; with neither, unit spacing. (`axis mins` are not read.)
// - NIfTI: the sform where sform_code > 0, else the qform where qform_code > 0, else the
//   pixdims at origin 0 (the standard's method 1). Both affines are kept for the writer.
// World frames: each file's affine stays in its own frame (NRRD: its `space`, often LPS;
// NIfTI: always RAS), so a volume read and written in one format keeps every number. Only a
// conversion between the formats converts: LPS ↔ RAS negates the affine's x and y rows, LAS ↔
// RAS its x row; other NRRD spaces (scanner-xyz, 3D-right-handed, unnamed) are taken as they
// are. A NIfTI file becomes an NRRD in `space: right-anterior-superior`.
// Any failure is a UserError("PATH: reason"), one line; what the libraries would print on
// stderr is kept off it.
//
// Writing keeps what the input carried where it still holds after resampling (through
// Volume::metadata): see writeVolume(). Not carried: NIfTI extensions and slice timing;
// NRRD thicknesses, axis mins and maxs, and sample units (see nrrd_format.cpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "volume.h"

namespace ddt {

enum class VolumeFormat { Nrrd, Nifti };

// Where +x, +y and +z of a file's world frame point: right, anterior, superior (NIfTI, and an
// NRRD in right-anterior-superior); left, anterior, superior; left, posterior, superior
// (DICOM's, usual in NRRD); Other: no anatomical meaning, or no world frame at all.
enum class WorldFrame { Ras, Las, Lps, Other };

// What a NIfTI header carried, as niftilib reads it.
struct NiftiMetadata {
    int version = 1;                      // 1 or 2
    int qform_code = 0, sform_code = 0;   // NIFTI_XFORM_*: 0 none, 1 scanner, 2 aligned, 3 Talairach, 4 MNI
    Affine qform, sform;                  // each meaningful where its code is > 0
    double scl_slope = 0, scl_inter = 0;  // slope 0: no scaling
    int xyz_units = 0, time_units = 0;    // NIFTI_UNITS_*
    double cal_min = 0, cal_max = 0;      // display window of physical values
    int intent_code = 0;
    double intent_p1 = 0, intent_p2 = 0, intent_p3 = 0;
    std::string intent_name, descrip, aux_file;
    int freq_dim = 0, phase_dim = 0, slice_dim = 0;  // which axis each is (1..3), 0 none
    double toffset = 0;
};

// What an NRRD header carried, with teem's names for its enums ("left-posterior-superior",
// "domain", "cell"); "" where a field was absent.
struct NrrdMetadata {
    std::string space;                     // "" also for a space given only by its dimension
    bool has_space = false;                // space or space dimension given (then 3)
    bool has_spacings = false;             // `spacings` given instead (no space)
    std::array<std::string, 3> space_units, kinds, centers, labels, units;
    std::string content, sample_units;
    std::vector<std::string> comments;
    std::vector<std::pair<std::string, std::string>> key_values;
    std::string encoding;                  // "raw", "gzip", "bzip2", "ascii", "hex"
};

struct VolumeMetadata {
    VolumeFormat format = VolumeFormat::Nrrd;
    std::vector<std::string> files;  // the header and data files read (never overwritten)
    std::array<uint32_t, 3> size{};  // the input's size
    Affine index_to_world;           // the input's Volume::index_to_world
    WorldFrame frame = WorldFrame::Other;
    bool has_world = false;          // false: spacings only (NIfTI method 1, NRRD without space)
    bool compressed = false;         // .nii.gz, or an NRRD in gzip or bzip2
    std::optional<NiftiMetadata> nifti;
    std::optional<NrrdMetadata> nrrd;
};

// The format a path's extension names, any case: .nrrd and .nhdr NRRD, .nii and .nii.gz NIfTI.
std::optional<VolumeFormat> volumeFormatOf(const std::string& path);
inline bool isVolumePath(const std::string& path) { return volumeFormatOf(path).has_value(); }
// ".nrrd, .nhdr, .nii or .nii.gz", for messages.
std::string volumeExtensionNames();
// `path` without the volume extension it ends in (both parts of .nii.gz); unchanged without one.
std::string withoutVolumeExtension(const std::string& path);

// "uint8", "int8", "uint16", "int16", "float32", "float64", for messages.
const char* voxelTypeName(VoxelType type);

// Reads a volume (see the top of this file). Throws UserError("PATH: reason").
Volume readVolume(const std::string& path);

// "" if a volume of `size` voxels can be written to `path` (its extension names a volume
// format, its folder exists, the size is within the limits), else the reason; for the CLI
// to ask before any work.
std::string volumeOutputProblem(const std::string& path, const std::array<uint32_t, 3>& size);

// Writes `volume` to `path` in the format its extension names, with `type` samples: integer
// types hold the values rounded to the nearest integer and clamped to the type's range (a
// note counts the clamped ones); float64 holds the float values. `volume.index_to_world` is
// the output's geometry. From volume.metadata (the input's), where present:
// - NIfTI → NIfTI: both qform and sform with their codes, each moved by the index map that
//   turns the input's affine into volume.index_to_world (resampledAffine() for a resampled
//   volume); xyzt units, intent, description, cal_min/max, dim_info. An integer output of a
//   scaled input keeps its scl_slope and scl_inter (the samples are stored unscaled, so the
//   values round-trip); a float output is stored unscaled (slope 1). NIfTI-2 stays NIfTI-2.
// - NRRD → NRRD: space, space directions, space origin, space units, kinds, centers, labels,
//   units, content, sample units, comments and key/value pairs; spacings where the input had
//   only spacings; gzip where the input was compressed.
// - across formats: the affine converted between the frames (top of this file); a NIfTI
//   output gets sform and qform with code 1 (scanner), the qform only where the axes are
//   orthogonal (a qform cannot shear); an NRRD output a space where the NIfTI had a qform or
//   sform. Files without a world frame stay so: only the spacings are written.
// A .nii.gz or .nhdr (+ .raw or .raw.gz beside it) output is compressed as the path or the
// input says. Every file goes to a temporary file beside it that is renamed into place once
// all is written (for .nhdr, the data file first); a file the volume was read from is never
// replaced. Returns notes for the user ("PATH: 12 samples were clamped to the uint8 range").
// Throws UserError("PATH: reason"), leaving the output as it was.
std::vector<std::string> writeVolume(const std::string& path, const Volume& volume, VoxelType type);

}  // namespace ddt
