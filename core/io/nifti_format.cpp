// NIfTI-1 and NIfTI-2 volumes (.nii, .nii.gz) through niftilib's nifti2 library (3.0,
// Debian 12's libnifti2), which reads both versions.
// The library reads and writes the headers. The samples are read and written here, through
// its znzlib for reading: nifti_image_load() silently sets NaN and infinite floats to 0 (its
// nifti_read_buffer), which would hide what ddtup refuses, and nifti_image_write() returns no
// status at all (a full disk passes unseen), so the output goes through VolumeOutputFile.
// At debug level 0 the library prints nothing for the failures it returns; they get their
// reason from the checks here.
#include <sys/stat.h>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

#include <nifti2_io.h>

#include "volume_formats.h"

namespace ddt {

namespace {

// .nii.gz, any case.
bool isGzipPath(const std::string& path) {
    return path.size() > 3 && path[path.size() - 3] == '.' && std::tolower(static_cast<unsigned char>(path[path.size() - 2])) == 'g' &&
           std::tolower(static_cast<unsigned char>(path[path.size() - 1])) == 'z';
}

struct NiftiImageDeleter {
    void operator()(nifti_image* image) const { nifti_image_free(image); }
};
using NiftiImagePtr = std::unique_ptr<nifti_image, NiftiImageDeleter>;

struct ZnzCloser {
    void operator()(znzptr* file) const {
        znzFile handle = file;
        znzclose(handle);
    }
};
using ZnzPtr = std::unique_ptr<znzptr, ZnzCloser>;

// The library's settings are process-wide: set them once.
void configureLibrary() {
    static std::once_flag once;
    std::call_once(once, [] {
        nifti_set_debug_level(0);        // no messages on stderr
        nifti_set_allow_upper_fext(1);   // .NII and .NII.GZ too, as volumeFormatOf() accepts
        nifti_set_skip_blank_ext(1);     // no empty extension block on write (unused: we write)
    });
}

std::optional<VoxelType> sampleTypeOfNifti(int datatype) {
    switch (datatype) {
        case NIFTI_TYPE_UINT8: return VoxelType::u8;
        case NIFTI_TYPE_INT8: return VoxelType::i8;
        case NIFTI_TYPE_UINT16: return VoxelType::u16;
        case NIFTI_TYPE_INT16: return VoxelType::i16;
        case NIFTI_TYPE_FLOAT32: return VoxelType::f32;
        case NIFTI_TYPE_FLOAT64: return VoxelType::f64;
        default: return std::nullopt;
    }
}

int niftiTypeOf(VoxelType type) {
    switch (type) {
        case VoxelType::u8: return NIFTI_TYPE_UINT8;
        case VoxelType::i8: return NIFTI_TYPE_INT8;
        case VoxelType::u16: return NIFTI_TYPE_UINT16;
        case VoxelType::i16: return NIFTI_TYPE_INT16;
        case VoxelType::f32: return NIFTI_TYPE_FLOAT32;
        case VoxelType::f64: break;
    }
    return NIFTI_TYPE_FLOAT64;
}

std::string dimsOf(const nifti_image& image) {
    std::string text;
    for (int64_t d = 1; d <= image.dim[0] && d <= 7; ++d) text += (d > 1 ? " × " : "") + std::to_string(image.dim[d]);
    return text;
}

// "" when the header describes a plain scalar volume ddtup reads, else the reason.
std::string layoutProblem(const nifti_image& image) {
    if (image.nifti_type != NIFTI_FTYPE_NIFTI1_1 && image.nifti_type != NIFTI_FTYPE_NIFTI2_1)
        return "not a single-file NIfTI-1 or NIfTI-2 image (no n+1 or n+2 magic)";
    const int datatype = image.datatype;
    if (datatype == NIFTI_TYPE_RGB24 || datatype == NIFTI_TYPE_RGBA32)
        return std::string(nifti_datatype_string(datatype)) + " samples: multi-component data; ddtup reads scalar volumes";
    if (!sampleTypeOfNifti(datatype))
        return "sample type " + std::string(nifti_datatype_string(datatype)) +
               " is not supported (ddtup reads UINT8, INT8, UINT16, INT16, FLOAT32 and FLOAT64)";
    // dim[4] is time, dim[5] the components of a vector or matrix per voxel (the standard).
    const int64_t ndim = image.dim[0];
    if (ndim >= 5 && image.dim[5] > 1)
        return std::to_string(image.dim[5]) + " values per voxel (" + dimsOf(image) +
               "): multi-component data; ddtup reads scalar volumes";
    if (ndim >= 4 && image.dim[4] > 1)
        return "a 4-D series of " + std::to_string(image.dim[4]) + " volumes (" + dimsOf(image) +
               "); ddtup reads single 3-D volumes";
    for (int64_t d = 6; d <= ndim && d <= 7; ++d)
        if (image.dim[d] > 1) return std::to_string(ndim) + "-D data (" + dimsOf(image) + "); ddtup reads 3-D scalar volumes";
    if (ndim < 3) return std::to_string(ndim) + "-D data (" + dimsOf(image) + "), not a volume; ddtup reads 3-D scalar volumes";
    for (int d = 1; d <= 3; ++d)
        if (image.dim[d] > int64_t(kMaxVolumeSide))
            return dimsOf(image) + " voxels: a side above " + std::to_string(kMaxVolumeSide) + " voxels, ddtup's limit";
    return volumeSizeProblem({uint32_t(image.nx), uint32_t(image.ny), uint32_t(image.nz)});
}

Affine affineOf(const nifti_dmat44& matrix) {
    Affine affine;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) affine.m[r][c] = matrix.m[r][c];
    return affine;
}

nifti_dmat44 matrixOf(const Affine& affine) {
    nifti_dmat44 matrix{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) matrix.m[r][c] = affine.m[r][c];
    matrix.m[3][3] = 1;
    return matrix;
}

// The standard's method 1, for files with neither transform: the pixdims along the index
// axes, origin 0. A pixdim that is not a positive length counts as 1.
Affine pixdimAffine(const nifti_image& image) {
    Affine affine;
    const double pixdims[3] = {image.dx, image.dy, image.dz};
    for (int a = 0; a < 3; ++a) affine.m[a][a] = std::isfinite(pixdims[a]) && pixdims[a] > 0 ? pixdims[a] : 1.0;
    return affine;
}

// 1 or 2. The nifti_image does not say: the library marks NIfTI-2 files NIFTI_FTYPE_NIFTI1_1
// too (nifti_convert_n2hdr2nim), so the header is asked.
int niftiVersionOf(const std::string& path) {
    int version = 1;
    void* header = nifti_read_header(path.c_str(), &version, 0);
    std::free(header);
    return version == 2 ? 2 : 1;
}

NiftiMetadata metadataOf(const nifti_image& image, int version) {
    NiftiMetadata meta;
    meta.version = version;
    meta.qform_code = image.qform_code;
    meta.sform_code = image.sform_code;
    meta.qform = affineOf(image.qto_xyz);
    meta.sform = affineOf(image.sto_xyz);
    meta.scl_slope = image.scl_slope;
    meta.scl_inter = image.scl_inter;
    meta.xyz_units = image.xyz_units;
    meta.time_units = image.time_units;
    meta.cal_min = image.cal_min;
    meta.cal_max = image.cal_max;
    meta.intent_code = image.intent_code;
    meta.intent_p1 = image.intent_p1;
    meta.intent_p2 = image.intent_p2;
    meta.intent_p3 = image.intent_p3;
    meta.intent_name = std::string(image.intent_name, strnlen(image.intent_name, sizeof image.intent_name));
    meta.descrip = std::string(image.descrip, strnlen(image.descrip, sizeof image.descrip));
    meta.aux_file = std::string(image.aux_file, strnlen(image.aux_file, sizeof image.aux_file));
    meta.freq_dim = image.freq_dim;
    meta.phase_dim = image.phase_dim;
    meta.slice_dim = image.slice_dim;
    meta.toffset = image.toffset;
    return meta;
}

// The samples as stored (native byte order once swapped). Exactly the header's bytes must
// follow its offset: fewer is a truncated file, more a header whose sizes are too small.
std::unique_ptr<unsigned char[]> readSamples(const std::string& path, const nifti_image& image) {
    const uint64_t count = uint64_t(image.nvox) * uint64_t(image.nbyper);
    const std::string described = "the header describes " + std::to_string(count) + " bytes of samples (" + dimsOf(image) +
                                  " " + nifti_datatype_string(image.datatype) + ") from byte " +
                                  std::to_string(image.iname_offset);
    const bool gzipped = nifti_is_gzfile(image.iname) != 0;
    if (image.iname_offset < 0) throw UserError(path + ": the header gives a negative data offset");
    if (!gzipped) {
        struct stat status {};
        if (::stat(image.iname, &status) == 0) {
            const uint64_t held = uint64_t(status.st_size) > uint64_t(image.iname_offset)
                                      ? uint64_t(status.st_size) - uint64_t(image.iname_offset)
                                      : 0;
            if (held < count) throw UserError(path + ": truncated: " + described + ", the file holds " + std::to_string(held));
            if (held > count)
                throw UserError(path + ": " + described + ", the file holds " + std::to_string(held) +
                                ": the header does not match the data");
        }
    }
    ZnzPtr file(znzopen(image.iname, "rb", gzipped ? 1 : 0));
    if (!file) throw UserError(path + ": cannot open (" + std::strerror(errno) + ")");
    // Not zeroed: pages are touched only as the data arrives, so that a .nii.gz whose header
    // claims gigabytes that are not there fails before taking them.
    std::unique_ptr<unsigned char[]> bytes = std::make_unique_for_overwrite<unsigned char[]>(count);
    if (znzseek(file.get(), znz_off_t(image.iname_offset), SEEK_SET) < 0)
        throw UserError(path + ": truncated: " + described + ", the file ends before it");
    const size_t read = znzread(bytes.get(), 1, count, file.get());
    if (read < count)
        throw UserError(path + ": truncated or corrupt: " + described + ", " + std::to_string(read) + " could be read");
    unsigned char extra = 0;
    if (znzread(&extra, 1, 1, file.get()) == 1)
        throw UserError(path + ": " + described + ", and more follow: the header does not match the data");
    if (image.swapsize > 1 && image.byteorder != nifti_short_order())
        nifti_swap_Nbytes(int64_t(image.nvox), image.swapsize, bytes.get());
    return bytes;
}

}  // namespace

Volume readNifti(const std::string& path) {
    configureLibrary();
    NiftiImagePtr image(nifti_image_read(path.c_str(), 0));
    if (!image) {
        struct stat status {};
        if (::stat(path.c_str(), &status) == 0 && status.st_size < 348 && nifti_is_gzfile(path.c_str()) == 0)
            throw UserError(path + ": truncated: " + std::to_string(status.st_size) +
                            " bytes, fewer than a NIfTI header takes (348)");
        throw UserError(path + ": not a readable NIfTI-1 or NIfTI-2 file (its header is missing or damaged)");
    }
    if (std::string problem = layoutProblem(*image); !problem.empty()) throw UserError(path + ": " + problem);

    Volume volume;
    volume.size = {uint32_t(image->nx), uint32_t(image->ny), uint32_t(image->nz)};
    volume.type = *sampleTypeOfNifti(image->datatype);
    const std::unique_ptr<unsigned char[]> samples = readSamples(path, *image);
    // A slope of 0 means no scaling (the standard); one that is not finite cannot be applied.
    const double slope = std::isfinite(image->scl_slope) ? image->scl_slope : 0.0;
    const double inter = slope != 0 && std::isfinite(image->scl_inter) ? image->scl_inter : 0.0;
    volume.values = physicalValues(path, samples.get(), volume.type, volume.size, slope, inter);

    auto metadata = std::make_shared<VolumeMetadata>();
    metadata->format = VolumeFormat::Nifti;
    metadata->files = {path};
    metadata->size = volume.size;
    metadata->nifti = metadataOf(*image, niftiVersionOf(path));
    metadata->nifti->scl_slope = slope;
    metadata->nifti->scl_inter = inter;
    if (image->sform_code > 0) volume.index_to_world = metadata->nifti->sform;
    else if (image->qform_code > 0) volume.index_to_world = metadata->nifti->qform;
    else volume.index_to_world = pixdimAffine(*image);
    metadata->index_to_world = volume.index_to_world;
    metadata->has_world = image->sform_code > 0 || image->qform_code > 0;
    metadata->frame = metadata->has_world ? WorldFrame::Ras : WorldFrame::Other;
    metadata->compressed = isGzipPath(path);
    volume.metadata = std::move(metadata);
    return volume;
}

namespace {

// NRRD space units as NIfTI's xyz units (NIFTI_UNITS_*), where all three axes agree.
int unitsOf(const std::array<std::string, 3>& units) {
    if (units[0] != units[1] || units[0] != units[2]) return NIFTI_UNITS_UNKNOWN;
    if (units[0] == "mm" || units[0] == "millimeter" || units[0] == "millimeters") return NIFTI_UNITS_MM;
    if (units[0] == "um" || units[0] == "micron" || units[0] == "microns" || units[0] == "µm") return NIFTI_UNITS_MICRON;
    if (units[0] == "m" || units[0] == "meter" || units[0] == "meters") return NIFTI_UNITS_METER;
    return NIFTI_UNITS_UNKNOWN;
}

void copyText(char* field, size_t field_size, const std::string& text) {
    std::memset(field, 0, field_size);
    std::memcpy(field, text.data(), std::min(text.size(), field_size - 1));
}

// Sets the qform fields (quaternion, offset, qfac, pixdims) from `qform`, through the
// library's decomposition.
void setQform(nifti_image& image, const Affine& qform) {
    nifti_dmat44_to_quatern(matrixOf(qform), &image.quatern_b, &image.quatern_c, &image.quatern_d, &image.qoffset_x,
                            &image.qoffset_y, &image.qoffset_z, &image.dx, &image.dy, &image.dz, &image.qfac);
    image.qto_xyz = nifti_quatern_to_dmat44(image.quatern_b, image.quatern_c, image.quatern_d, image.qoffset_x,
                                           image.qoffset_y, image.qoffset_z, image.dx, image.dy, image.dz, image.qfac);
}

// The output's header: geometry (both transforms), scaling and what the input carried.
// Returns the scaling the samples are to be stored with (slope 0: none).
std::pair<double, double> describe(nifti_image& image, const Volume& volume, VoxelType type) {
    const VolumeMetadata* input = volume.metadata.get();
    const NiftiMetadata* same = input && input->nifti ? &*input->nifti : nullptr;
    const NrrdMetadata* nrrd = input && input->nrrd ? &*input->nrrd : nullptr;
    const bool has_world = input ? input->has_world : true;
    const Affine affine = convertFrame(volume.index_to_world, input ? input->frame : WorldFrame::Other, WorldFrame::Ras);
    const std::array<double, 3> spacing = spacingOf(affine);

    Affine qform = affine, sform = affine;
    int qform_code = 0, sform_code = 0;
    if (same) {
        // The primary transform is the volume's; the other moves by the same index map.
        qform_code = same->qform_code;
        sform_code = same->sform_code;
        if (sform_code > 0 && qform_code > 0) qform = followIndexMap(same->qform, input->index_to_world, volume.index_to_world);
    } else if (has_world) {
        sform_code = NIFTI_XFORM_SCANNER_ANAT;
        qform_code = hasOrthogonalAxes(affine) ? NIFTI_XFORM_SCANNER_ANAT : NIFTI_XFORM_UNKNOWN;
    }
    image.qform_code = std::max(qform_code, 0);
    image.sform_code = std::max(sform_code, 0);
    image.dx = spacing[0];
    image.dy = spacing[1];
    image.dz = spacing[2];
    if (image.qform_code > 0) setQform(image, qform);
    if (image.sform_code > 0) image.sto_xyz = matrixOf(sform);
    image.pixdim[1] = image.dx;
    image.pixdim[2] = image.dy;
    image.pixdim[3] = image.dz;

    // Integer samples of a scaled input keep its scaling, so that its values round-trip.
    const bool integer = type != VoxelType::f32 && type != VoxelType::f64;
    const bool keep_scaling = integer && same && same->scl_slope != 0;
    const double slope = keep_scaling ? same->scl_slope : 0.0, inter = keep_scaling ? same->scl_inter : 0.0;
    image.scl_slope = keep_scaling ? slope : 1.0;
    image.scl_inter = keep_scaling ? inter : 0.0;

    if (same) {
        image.xyz_units = same->xyz_units;
        image.time_units = same->time_units;
        image.cal_min = same->cal_min;
        image.cal_max = same->cal_max;
        image.intent_code = same->intent_code;
        image.intent_p1 = same->intent_p1;
        image.intent_p2 = same->intent_p2;
        image.intent_p3 = same->intent_p3;
        copyText(image.intent_name, sizeof image.intent_name, same->intent_name);
        copyText(image.descrip, sizeof image.descrip, same->descrip);
        copyText(image.aux_file, sizeof image.aux_file, same->aux_file);
        image.freq_dim = same->freq_dim;
        image.phase_dim = same->phase_dim;
        image.slice_dim = same->slice_dim;
        image.toffset = same->toffset;
    } else if (nrrd) {
        image.xyz_units = has_world ? unitsOf(nrrd->space_units) : NIFTI_UNITS_UNKNOWN;
        copyText(image.descrip, sizeof image.descrip, nrrd->content);
    }
    // The slice timing describes the acquired slices, which resampling does not keep.
    image.slice_code = 0;
    image.slice_start = 0;
    image.slice_end = 0;
    image.slice_duration = 0;
    return {slope, inter};
}

// Writes `data` to `out`, through gzip when `gzip`. Throws out.failure() on any failure.
class NiftiSink {
public:
    NiftiSink(VolumeOutputFile& out, bool gzip) : out_(out), gzip_(gzip) {
        if (gzip_ && deflateInit2(&stream_, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
            throw out_.failure("zlib cannot start");
    }
    ~NiftiSink() {
        if (gzip_) deflateEnd(&stream_);
    }
    NiftiSink(const NiftiSink&) = delete;
    NiftiSink& operator=(const NiftiSink&) = delete;

    void write(const void* data, size_t size) {
        if (!gzip_) {
            if (std::fwrite(data, 1, size, out_.stream()) != size) throw out_.failure("write failed");
            return;
        }
        const unsigned char* bytes = static_cast<const unsigned char*>(data);
        while (size > 0) {  // zlib counts in unsigned int
            const size_t piece = std::min<size_t>(size, size_t(1) << 30);
            deflateSome(bytes, piece, Z_NO_FLUSH);
            bytes += piece;
            size -= piece;
        }
    }
    void finish() {
        if (gzip_) deflateSome(nullptr, 0, Z_FINISH);
    }

private:
    void deflateSome(const unsigned char* data, size_t size, int flush) {
        stream_.next_in = const_cast<unsigned char*>(data);  // zlib does not write through it
        stream_.avail_in = unsigned(size);
        unsigned char buffer[1 << 16];
        int status = Z_OK;
        do {
            stream_.next_out = buffer;
            stream_.avail_out = sizeof buffer;
            status = deflate(&stream_, flush);
            if (status == Z_STREAM_ERROR) throw out_.failure("zlib failed");
            const size_t produced = sizeof buffer - stream_.avail_out;
            if (std::fwrite(buffer, 1, produced, out_.stream()) != produced) throw out_.failure("write failed");
        } while (stream_.avail_out == 0 || (flush == Z_FINISH && status != Z_STREAM_END));
    }

    VolumeOutputFile& out_;
    bool gzip_;
    z_stream stream_{};
};

}  // namespace

void writeNifti(const std::string& path, const Volume& volume, VoxelType type, std::vector<std::string>& notes) {
    configureLibrary();
    const NiftiMetadata* same = volume.metadata && volume.metadata->nifti ? &*volume.metadata->nifti : nullptr;
    // NIfTI-1 holds sides up to 32 767; NIfTI-2 anything, and stays NIfTI-2.
    const bool nifti2 = (same && same->version == 2) || volume.size[0] > 32767 || volume.size[1] > 32767 || volume.size[2] > 32767;
    const int64_t dims[8] = {3, volume.size[0], volume.size[1], volume.size[2], 1, 1, 1, 1};
    NiftiImagePtr image(nifti_make_new_nim(dims, niftiTypeOf(type), 0));
    if (!image) throw UserError(path + ": cannot write (niftilib cannot make the header)");
    const auto [slope, inter] = describe(*image, volume, type);
    image->nifti_type = nifti2 ? NIFTI_FTYPE_NIFTI2_1 : NIFTI_FTYPE_NIFTI1_1;
    // The header, the 4-byte extension flag (no extensions), then the samples.
    image->iname_offset = nifti2 ? int64_t(sizeof(nifti_2_header)) + 4 : int64_t(sizeof(nifti_1_header)) + 4;

    nifti_1_header header1{};
    nifti_2_header header2{};
    if (nifti2 ? nifti_convert_nim2n2hdr(image.get(), &header2) : nifti_convert_nim2n1hdr(image.get(), &header1))
        throw UserError(path + ": cannot write (niftilib cannot make the header)");

    const StoredSamples samples = storedSamples(volume.values, type, slope, inter);
    noteClamped(path, samples, type, notes);
    VolumeOutputFile out(path);
    {
        NiftiSink sink(out, isGzipPath(path));
        if (nifti2) sink.write(&header2, sizeof header2);
        else sink.write(&header1, sizeof header1);
        const unsigned char no_extensions[4] = {0, 0, 0, 0};
        sink.write(no_extensions, sizeof no_extensions);
        sink.write(samples.bytes.data(), samples.bytes.size());
        sink.finish();
    }
    out.commit();
}

}  // namespace ddt
