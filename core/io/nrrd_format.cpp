// NRRD volumes through teem's nrrd library (Teem 1.12, Debian 12's libteem).
// Teem reports failures through biff, a global message store: each call's messages are read
// with biffGetDone() and turned into the one line the user gets. Biff and teem's settings are
// process-wide and not thread-safe, so every use of teem holds one mutex.
#include <sys/stat.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>

#include <teem/nrrd.h>

#include "volume_formats.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

std::mutex teem_mutex;

struct NrrdDeleter {
    void operator()(Nrrd* nrrd) const { nrrdNuke(nrrd); }  // the struct and its data
};
struct WrappedNrrdDeleter {
    void operator()(Nrrd* nrrd) const { nrrdNix(nrrd); }  // the struct only: the data is ours
};
struct IoStateDeleter {
    void operator()(NrrdIoState* nio) const {
        // Left open by keepNrrdDataFileOpen; teem does not close it.
        if (nio->dataFile && nio->dataFile != stdin) std::fclose(nio->dataFile);
        nio->dataFile = nullptr;
        nrrdIoStateNix(nio);
    }
};
using NrrdPtr = std::unique_ptr<Nrrd, NrrdDeleter>;
using WrappedNrrdPtr = std::unique_ptr<Nrrd, WrappedNrrdDeleter>;
using IoStatePtr = std::unique_ptr<NrrdIoState, IoStateDeleter>;

// Teem's messages for the last failure, one line: biff keeps a line per function the failure
// passed through ("[nrrd] nrrdLoad: trouble reading …"), outermost first; the innermost says
// what went wrong.
std::string biffReason() {
    char* text = biffGetDone(NRRD);
    std::string message = text ? text : "";
    std::free(text);
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    if (size_t end = message.rfind('\n'); end != std::string::npos) message.erase(0, end + 1);
    if (message.starts_with("[nrrd] ")) message.erase(0, 7);
    // "_nrrdEncodingRaw_read: fread got only …": the function's name means nothing to a user.
    if (size_t colon = message.find(": "); colon != std::string::npos && message.find(' ') > colon) message.erase(0, colon + 2);
    while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
    return message.empty() ? "unknown error" : message;
}

std::string enumName(const airEnum* names, int value) {
    const char* name = airEnumStr(names, value);
    return name ? name : "unknown";
}

std::string sizesOf(const Nrrd& nrrd) {
    std::string text;
    for (unsigned a = 0; a < nrrd.dim; ++a) text += (a ? " × " : "") + std::to_string(nrrd.axis[a].size);
    return text;
}

std::optional<VoxelType> sampleTypeOfNrrd(int type) {
    switch (type) {
        case nrrdTypeUChar: return VoxelType::u8;
        case nrrdTypeChar: return VoxelType::i8;
        case nrrdTypeUShort: return VoxelType::u16;
        case nrrdTypeShort: return VoxelType::i16;
        case nrrdTypeFloat: return VoxelType::f32;
        case nrrdTypeDouble: return VoxelType::f64;
        default: return std::nullopt;
    }
}

int nrrdTypeOf(VoxelType type) {
    switch (type) {
        case VoxelType::u8: return nrrdTypeUChar;
        case VoxelType::i8: return nrrdTypeChar;
        case VoxelType::u16: return nrrdTypeUShort;
        case VoxelType::i16: return nrrdTypeShort;
        case VoxelType::f32: return nrrdTypeFloat;
        case VoxelType::f64: break;
    }
    return nrrdTypeDouble;
}

WorldFrame frameOfSpace(int space) {
    switch (space) {
        case nrrdSpaceRightAnteriorSuperior: return WorldFrame::Ras;
        case nrrdSpaceLeftAnteriorSuperior: return WorldFrame::Las;
        case nrrdSpaceLeftPosteriorSuperior: return WorldFrame::Lps;
        default: return WorldFrame::Other;
    }
}

// "" when the header describes a plain scalar volume ddtup reads, else the reason.
std::string layoutProblem(const Nrrd& nrrd) {
    // An axis that does not sample space: a component (vector, colour, list…) or time.
    for (unsigned a = 0; a < nrrd.dim; ++a) {
        const int kind = nrrd.axis[a].kind;
        if (kind == nrrdKindUnknown || kind == nrrdKindDomain || kind == nrrdKindSpace) continue;
        const std::string what = "axis " + std::to_string(a) + " (" + std::to_string(nrrd.axis[a].size) + " samples) is of kind " +
                                 enumName(nrrdKind, kind);
        if (kind == nrrdKindTime) return what + ": a time series; ddtup reads single 3-D scalar volumes";
        return what + ": multi-component samples; ddtup reads scalar volumes";
    }
    if (nrrd.dim < 3)
        return std::to_string(nrrd.dim) + "-D data (" + sizesOf(nrrd) + "), not a volume; ddtup reads 3-D scalar volumes";
    if (nrrd.dim > 3) return std::to_string(nrrd.dim) + "-D data (" + sizesOf(nrrd) + "); ddtup reads 3-D scalar volumes";
    if (nrrd.spaceDim != 0 && nrrd.spaceDim != 3)
        return "a " + std::to_string(nrrd.spaceDim) + "-D space (" + enumName(nrrdSpace, nrrd.space) +
               "); ddtup reads volumes in 3-D space";
    for (unsigned a = 0; a < 3 && nrrd.spaceDim == 3; ++a)
        if (!nrrdSpaceVecExists(3, nrrd.axis[a].spaceDirection))
            return "axis " + std::to_string(a) + " has no space direction (not a spatial axis); ddtup reads 3-D scalar volumes";
    if (!sampleTypeOfNrrd(nrrd.type))
        return "sample type " + enumName(nrrdType, nrrd.type) +
               " is not supported (ddtup reads 8- and 16-bit integers, float and double)";
    for (unsigned a = 0; a < 3; ++a)
        if (nrrd.axis[a].size > kMaxVolumeSide)
            return sizesOf(nrrd) + " voxels: a side above " + std::to_string(kMaxVolumeSide) + " voxels, ddtup's limit";
    return volumeSizeProblem({uint32_t(nrrd.axis[0].size), uint32_t(nrrd.axis[1].size), uint32_t(nrrd.axis[2].size)});
}

// The index-to-world affine: space directions and origin; else spacings; else unit spacing.
Affine affineOf(const Nrrd& nrrd) {
    Affine affine;
    for (int a = 0; a < 3; ++a) {
        const NrrdAxisInfo& axis = nrrd.axis[a];
        if (nrrd.spaceDim == 3) {
            for (int r = 0; r < 3; ++r) affine.m[r][a] = axis.spaceDirection[r];
        } else {
            affine.m[a][a] = std::isfinite(axis.spacing) ? axis.spacing : 1.0;
        }
    }
    if (nrrd.spaceDim == 3 && nrrdSpaceVecExists(3, nrrd.spaceOrigin))
        for (int r = 0; r < 3; ++r) affine.m[r][3] = nrrd.spaceOrigin[r];
    return affine;
}

NrrdMetadata metadataOf(const Nrrd& nrrd, const NrrdIoState& nio) {
    NrrdMetadata meta;
    meta.has_space = nrrd.spaceDim == 3;
    meta.space = nrrd.space != nrrdSpaceUnknown ? enumName(nrrdSpace, nrrd.space) : "";
    auto text = [](const char* s) { return std::string(s ? s : ""); };
    for (int a = 0; a < 3; ++a) {
        const NrrdAxisInfo& axis = nrrd.axis[a];
        meta.has_spacings = meta.has_spacings || (!meta.has_space && std::isfinite(axis.spacing));
        if (meta.has_space) meta.space_units[a] = text(nrrd.spaceUnits[a]);
        if (axis.kind != nrrdKindUnknown) meta.kinds[a] = enumName(nrrdKind, axis.kind);
        if (axis.center != nrrdCenterUnknown) meta.centers[a] = enumName(nrrdCenter, axis.center);
        meta.labels[a] = text(axis.label);
        meta.units[a] = text(axis.units);
    }
    meta.content = text(nrrd.content);
    meta.sample_units = text(nrrd.sampleUnits);
    for (unsigned i = 0; i < nrrd.cmtArr->len; ++i) meta.comments.push_back(text(nrrd.cmt[i]));
    for (unsigned i = 0; i < nrrd.kvpArr->len; ++i) meta.key_values.emplace_back(text(nrrd.kvp[2 * i]), text(nrrd.kvp[2 * i + 1]));
    meta.encoding = nio.encoding ? nio.encoding->name : "";
    return meta;
}

// The files a volume was read from: the header, and the detached data files the header names
// (relative to the header's folder).
std::vector<std::string> filesOf(const std::string& path, const NrrdIoState& nio) {
    std::vector<std::string> files{path};
    const fs::path folder = fs::path(path).parent_path();
    for (unsigned i = 0; i < nio.dataFNArr->len; ++i) {
        const fs::path name(nio.dataFN[i]);
        files.push_back((name.is_absolute() ? name : folder / name).string());
    }
    return files;
}

// A raw encoding's data must be exactly what the header describes: teem reads a truncated
// file as a failure but ignores bytes past the end (a header whose sizes are too small).
// `data_file` stands where the samples start.
std::string rawDataProblem(const Nrrd& nrrd, const NrrdIoState& nio, FILE* data_file) {
    if (nio.encoding != nrrdEncodingRaw || !data_file || nio.byteSkip < 0) return "";
    struct stat status {};
    const long start = std::ftell(data_file);
    if (start < 0 || ::fstat(fileno(data_file), &status) != 0 || !S_ISREG(status.st_mode)) return "";
    const uint64_t expected = uint64_t(nrrdElementNumber(&nrrd)) * nrrdElementSize(&nrrd);
    const uint64_t held = uint64_t(status.st_size) > uint64_t(start) ? uint64_t(status.st_size) - uint64_t(start) : 0;
    if (held == expected) return "";
    const std::string described = "the header describes " + std::to_string(expected) + " bytes of samples (" + sizesOf(nrrd) +
                                  " " + enumName(nrrdType, nrrd.type) + ")";
    if (held < expected) return "truncated: " + described + ", the file holds " + std::to_string(held);
    return described + ", the file holds " + std::to_string(held) + ": the header does not match the data";
}

}  // namespace

Volume readNrrd(const std::string& path) {
    std::lock_guard lock(teem_mutex);
    nrrdStateVerboseIO = 0;  // its warnings go to stderr; the checks below say more

    // The header first, so that nothing is allocated for a volume refused.
    NrrdPtr header(nrrdNew());
    IoStatePtr header_io(nrrdIoStateNew());
    header_io->skipData = AIR_TRUE;
    header_io->keepNrrdDataFileOpen = AIR_TRUE;
    if (nrrdLoad(header.get(), path.c_str(), header_io.get()) != 0)
        throw UserError(path + ": not a readable NRRD file (" + biffReason() + ")");
    if (std::string problem = layoutProblem(*header); !problem.empty()) throw UserError(path + ": " + problem);
    if (std::string problem = rawDataProblem(*header, *header_io, header_io->dataFile); !problem.empty())
        throw UserError(path + ": " + problem);

    NrrdPtr nrrd(nrrdNew());
    IoStatePtr nio(nrrdIoStateNew());
    if (nrrdLoad(nrrd.get(), path.c_str(), nio.get()) != 0)
        throw UserError(path + ": truncated or damaged samples (" + biffReason() + ")");
    // Again: the file may have changed since the header was read.
    if (std::string problem = layoutProblem(*nrrd); !problem.empty()) throw UserError(path + ": " + problem);

    Volume volume;
    volume.size = {uint32_t(nrrd->axis[0].size), uint32_t(nrrd->axis[1].size), uint32_t(nrrd->axis[2].size)};
    volume.type = *sampleTypeOfNrrd(nrrd->type);
    volume.index_to_world = affineOf(*nrrd);
    volume.values = physicalValues(path, nrrd->data, volume.type, volume.size);

    auto metadata = std::make_shared<VolumeMetadata>();
    metadata->format = VolumeFormat::Nrrd;
    metadata->files = filesOf(path, *nio);
    metadata->size = volume.size;
    metadata->index_to_world = volume.index_to_world;
    metadata->frame = nrrd->spaceDim == 3 ? frameOfSpace(nrrd->space) : WorldFrame::Other;
    metadata->has_world = nrrd->spaceDim == 3;
    metadata->compressed = nio->encoding && nio->encoding->isCompression;
    metadata->nrrd = metadataOf(*nrrd, *nio);
    volume.metadata = std::move(metadata);
    return volume;
}

namespace {

// NIfTI's xyz units as NRRD space units.
std::string unitName(int nifti_units) {
    switch (nifti_units) {
        case 1: return "m";   // NIFTI_UNITS_METER
        case 2: return "mm";  // NIFTI_UNITS_MM
        case 3: return "um";  // NIFTI_UNITS_MICRON
        default: return "";
    }
}

bool isDiagonal(const Affine& affine) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (r != c && affine.m[r][c] != 0) return false;
    return true;
}

// The output's header fields: geometry in the output's frame, and what the input carried.
void describe(Nrrd& nrrd, const Volume& volume) {
    const VolumeMetadata* input = volume.metadata.get();
    const NrrdMetadata* same = input && input->nrrd ? &*input->nrrd : nullptr;
    const NiftiMetadata* nifti = input && input->nifti ? &*input->nifti : nullptr;
    const bool has_world = input ? input->has_world : true;
    const WorldFrame from = input ? input->frame : WorldFrame::Other;

    // The space: the input NRRD's; RAS for a NIfTI with a world frame; an unnamed 3-D space
    // for a volume made in memory (its affine, no claim about anatomy).
    int space = nrrdSpaceUnknown;
    if (same && !same->space.empty()) space = airEnumVal(nrrdSpace, same->space.c_str());
    else if (nifti && has_world) space = nrrdSpaceRightAnteriorSuperior;
    const WorldFrame to = space == nrrdSpaceUnknown ? WorldFrame::Other : frameOfSpace(space);
    const Affine affine = convertFrame(volume.index_to_world, from, to);

    double directions[NRRD_DIM_MAX][NRRD_SPACE_DIM_MAX];
    if (has_world || !isDiagonal(affine)) {
        if (space != nrrdSpaceUnknown) nrrdSpaceSet(&nrrd, space);
        else nrrdSpaceDimensionSet(&nrrd, 3);
        // + 0.0 turns −0 into 0, which teem would print as "-0".
        double origin[NRRD_SPACE_DIM_MAX] = {affine.m[0][3] + 0.0, affine.m[1][3] + 0.0, affine.m[2][3] + 0.0};
        nrrdSpaceOriginSet(&nrrd, origin);
        for (int a = 0; a < 3; ++a)
            for (int r = 0; r < 3; ++r) directions[a][r] = affine.m[r][a] + 0.0;
        nrrdAxisInfoSet_nva(&nrrd, nrrdAxisInfoSpaceDirection, directions);
        for (int a = 0; a < 3; ++a) {
            const std::string units = same ? same->space_units[a] : nifti ? unitName(nifti->xyz_units) : "";
            if (!units.empty()) nrrd.spaceUnits[a] = airStrdup(units.c_str());
        }
    } else {
        // No world frame (spacings only, or a NIfTI of method 1): the origin cannot be said.
        double spacings[NRRD_DIM_MAX] = {affine.m[0][0], affine.m[1][1], affine.m[2][2]};
        nrrdAxisInfoSet_nva(&nrrd, nrrdAxisInfoSpacing, spacings);
    }

    int kinds[NRRD_DIM_MAX] = {nrrdKindDomain, nrrdKindDomain, nrrdKindDomain};
    int centers[NRRD_DIM_MAX] = {nrrdCenterUnknown, nrrdCenterUnknown, nrrdCenterUnknown};
    for (int a = 0; a < 3 && same; ++a) {
        kinds[a] = same->kinds[a].empty() ? nrrdKindUnknown : airEnumVal(nrrdKind, same->kinds[a].c_str());
        centers[a] = same->centers[a].empty() ? nrrdCenterUnknown : airEnumVal(nrrdCenter, same->centers[a].c_str());
    }
    nrrdAxisInfoSet_nva(&nrrd, nrrdAxisInfoKind, kinds);
    nrrdAxisInfoSet_nva(&nrrd, nrrdAxisInfoCenter, centers);
    if (same) {
        for (int a = 0; a < 3; ++a) {
            if (!same->labels[a].empty()) nrrd.axis[a].label = airStrdup(same->labels[a].c_str());
            if (!same->units[a].empty()) nrrd.axis[a].units = airStrdup(same->units[a].c_str());
        }
        if (!same->content.empty()) nrrd.content = airStrdup(same->content.c_str());
        // Not the sample units: Teem 1.12's writer allocates two bytes too few for the field's
        // quotes (write.c, nrrdField_sample_units; a heap overflow under AddressSanitizer).
        for (const std::string& comment : same->comments) nrrdCommentAdd(&nrrd, comment.c_str());
        for (const auto& [key, value] : same->key_values) nrrdKeyValueAdd(&nrrd, key.c_str(), value.c_str());
    } else if (nifti && !nifti->descrip.empty()) {
        nrrd.content = airStrdup(nifti->descrip.c_str());
    }
}

}  // namespace

void writeNrrd(const std::string& path, const Volume& volume, VoxelType type, std::vector<std::string>& notes) {
    const StoredSamples samples = storedSamples(volume.values, type);
    noteClamped(path, samples, type, notes);
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool detached = extension == ".nhdr";

    std::lock_guard lock(teem_mutex);
    nrrdStateVerboseIO = 0;
    WrappedNrrdPtr nrrd(nrrdNew());
    size_t sizes[NRRD_DIM_MAX] = {volume.size[0], volume.size[1], volume.size[2]};
    // nrrdWrap_nva does not write through the pointer; it is not const only in C.
    if (nrrdWrap_nva(nrrd.get(), const_cast<unsigned char*>(samples.bytes.data()), nrrdTypeOf(type), 3, sizes) != 0)
        throw UserError(path + ": cannot write (" + biffReason() + ")");
    describe(*nrrd, volume);
    if (volume.metadata && volume.metadata->nrrd && !volume.metadata->nrrd->sample_units.empty())
        notes.push_back(path + ": the sample units (" + volume.metadata->nrrd->sample_units +
                        ") are left out: teem 1.12 cannot write them safely");

    IoStatePtr nio(nrrdIoStateNew());
    nio->format = nrrdFormatNRRD;
    const bool compressed = volume.metadata ? volume.metadata->compressed : false;
    nio->encoding = compressed ? nrrdEncodingGzip : nrrdEncodingRaw;

    if (!detached) {
        VolumeOutputFile out(path);
        if (nrrdWrite(out.stream(), nrrd.get(), nio.get()) != 0) throw out.failure(biffReason());
        out.commit();
        return;
    }

    // A detached header (.nhdr): the samples go to STEM.raw (or .raw.gz) beside it, which the
    // header names relative to itself; the data file is written first, so that a header never
    // names a file that is not there.
    const fs::path header_path(path);
    const std::string stem = header_path.stem().string();
    const std::string data_name = stem + "." + nio->encoding->suffix;
    const std::string data_path = (header_path.parent_path() / data_name).string();
    refuseInputFile(data_path, volume);
    {
        VolumeOutputFile data(data_path);
        if (nio->encoding->write(data.stream(), samples.bytes.data(), volume.voxelCount(), nrrd.get(), nio.get()) != 0)
            throw data.failure(biffReason());
        data.commit();
    }
    nio->detachedHeader = AIR_TRUE;
    nio->skipData = AIR_TRUE;
    const std::string folder = header_path.parent_path().empty() ? "." : header_path.parent_path().string();
    nio->path = airStrdup(folder.c_str());
    nio->base = airStrdup(stem.c_str());
    VolumeOutputFile out(path);
    if (nrrdWrite(out.stream(), nrrd.get(), nio.get()) != 0) throw out.failure(biffReason());
    out.commit();
}

}  // namespace ddt
