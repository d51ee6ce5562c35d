// The volume formats behind volume_file.h, one file each (nrrd_format.cpp, nifti_format.cpp),
// and what they share (volume_file.cpp): sample conversion, world frames, the output file.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "checked_file.h"
#include "temp_files.h"
#include "user_error.h"
#include "volume_file.h"

namespace ddt {

// Each takes a path volume_file.cpp has checked (an existing regular file of that format's
// extension) and throws UserError("PATH: reason").
Volume readNrrd(const std::string& path);
Volume readNifti(const std::string& path);
// Each appends its notes; the path is checked, and is none of the input's files.
void writeNrrd(const std::string& path, const Volume& volume, VoxelType type, std::vector<std::string>& notes);
void writeNifti(const std::string& path, const Volume& volume, VoxelType type, std::vector<std::string>& notes);

// Throws UserError("OUTPUT: is the input file; …") when `output` is one of the files
// `volume` was read from (its metadata's files).
void refuseInputFile(const std::string& output, const Volume& volume);

// ---- Samples.

size_t sampleSize(VoxelType type);

// The physical values of `size` voxels of `type` at `data` (native byte order): raw · slope +
// inter where slope is not 0, else raw. Throws UserError("NAME: …") naming the first voxel
// whose value is NaN or infinite (or beyond float's range once scaled).
std::vector<float> physicalValues(const std::string& name, const void* data, VoxelType type,
                                  const std::array<uint32_t, 3>& size, double slope = 0, double inter = 0);

// `values` stored as `type` (native byte order): (value − inter) / slope where slope is not 0;
// integer types rounded to the nearest and clamped to their range (NaN becomes 0).
struct StoredSamples {
    std::vector<unsigned char> bytes;
    uint64_t clamped = 0;  // values outside the type's range
};
StoredSamples storedSamples(const std::vector<float>& values, VoxelType type, double slope = 0, double inter = 0);

// "PATH: N samples were clamped to the TYPE range", or nothing.
void noteClamped(const std::string& path, const StoredSamples& samples, VoxelType type, std::vector<std::string>& notes);

// ---- Geometry.

// `affine` re-expressed from world frame `from` to `to`: LPS ↔ RAS negates rows x and y,
// LAS ↔ RAS row x; Other converts to and from nothing.
Affine convertFrame(const Affine& affine, WorldFrame from, WorldFrame to);

// `other` moved by the index map M that takes the input's affine to the output's
// (output = input · M): other · M. For a resampled volume, M is resampledAffine()'s, so this is
// resampledAffine(other, …). `input` must be invertible; a singular one leaves `other` as is.
Affine followIndexMap(const Affine& other, const Affine& input, const Affine& output);

// Whether the three columns are pairwise orthogonal (relative to their lengths, 1e-6).
bool hasOrthogonalAxes(const Affine& affine);

// ---- Output.

// One output file: a temporary file beside `path` (output_file.h) written through a stdio
// stream whose every write goes to a CheckedFile, so that a full disk or a failed write is
// seen whatever the library writing into the stream checks; commit() renames it into place.
class VolumeOutputFile {
public:
    explicit VolumeOutputFile(const std::string& path);
    ~VolumeOutputFile();
    VolumeOutputFile(const VolumeOutputFile&) = delete;
    VolumeOutputFile& operator=(const VolumeOutputFile&) = delete;

    FILE* stream() { return stream_; }
    // Throws UserError("PATH: reason") for any failed write, else renames the file into place.
    void commit();
    // UserError("PATH: reason") for a failure the writer saw: the file's errno where a write
    // failed, else `what` (a library's message).
    UserError failure(const std::string& what);

private:
    std::string path_;
    std::unique_ptr<TempFile> temp_;
    std::unique_ptr<CheckedFile> file_;
    FILE* stream_ = nullptr;
};

}  // namespace ddt
