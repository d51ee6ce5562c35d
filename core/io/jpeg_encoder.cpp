#include "jpeg_encoder.h"

// jpeglib.h needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "parallel.h"
#include "sample_quantise.h"

namespace ddt {

namespace {

// Rows converted at a time: a few MiB of samples, whatever the size of the caller's band.
constexpr size_t kSliceBytes = size_t(4) << 20;
// Bytes libjpeg fills before they go to the sink.
constexpr size_t kOutputBufferBytes = size_t(64) << 10;
// The most data a marker holds: its 16-bit length counts itself.
constexpr size_t kMaxMarkerData = 65533;
// An ICC chunk: "ICC_PROFILE", NUL, its number and the count (1-based), then up to
// 65519 bytes of the profile (the marker's 65533 less those 14).
constexpr size_t kIccHeader = 14;
constexpr size_t kIccChunkData = kMaxMarkerData - kIccHeader;

// libjpeg reports fatal errors here: the message is kept and control jumps back to `run`.
struct ErrorManager {
    jpeg_error_mgr base;  // first, so that libjpeg's jpeg_error_mgr* is this
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void failHere(j_common_ptr info) {
    ErrorManager& errors = *reinterpret_cast<ErrorManager*>(info->err);
    (*info->err->format_message)(info, errors.message);
    std::longjmp(errors.jump, 1);
}

// Warnings and traces stay silent; compression has no warning about the output.
void ignoreMessage(j_common_ptr, int) {}

// The JFIF density from the resolution, as OpenImageIO 2.4 decided it: a pixel aspect ratio
// overrides the resolution it contradicts, in the inverted sense Photoshop and Nuke use
// (aspect = x density / y density), and missing values are filled in from the others.
void setDensity(const ImageAttributes& attributes, jpeg_compress_struct& info) {
    const std::string unit = attributes.getString("ResolutionUnit");
    info.density_unit = sameName(unit, "in") ? 1 : sameName(unit, "cm") ? 2 : 0;
    float x = attributes.getFloat("XResolution");
    float y = attributes.getFloat("YResolution");
    float aspect = attributes.getFloat("PixelAspectRatio");
    if (aspect <= 0.0f) {
        if (x <= 0.0f && y <= 0.0f) {  // nothing known: 1:1, valid and square
            info.X_density = info.Y_density = 1;
            return;
        }
        if (x <= 0.0f) x = y;
        if (y <= 0.0f) y = x;
    } else if (x <= 0.0f && y <= 0.0f) {
        if (aspect >= 1.0f) {
            x = 72.0f;
            y = x * aspect;
        } else {
            y = 72.0f;
            x = y * aspect;
        }
    } else if (x <= 0.0f) {
        x = y * aspect;
    } else {
        y = x / aspect;
    }
    // int() of a NaN or of a float out of int's range is what x86 makes of it (INT_MIN),
    // which the clamp turns into 1, as in OpenImageIO; spelled out to stay defined.
    auto density = [](float value) {
        const float rounded = value + 0.5f;
        if (!(rounded > -2147483648.0f && rounded < 2147483648.0f)) return UINT16(1);
        return UINT16(std::clamp(int(rounded), 1, 65535));
    };
    info.X_density = density(x);
    info.Y_density = density(y);
}

// "jpeg:subsampling"'s horizontal and vertical factors of Y (Cb and Cr keep 1×1), or null for
// libjpeg's default.
const int* subsamplingFactors(const std::string& name) {
    static const int k444[2] = {1, 1}, k422[2] = {2, 1}, k420[2] = {2, 2}, k411[2] = {4, 1};
    if (name == "4:4:4") return k444;
    if (name == "4:2:2") return k422;
    if (name == "4:2:0") return k420;
    if (name == "4:1:1") return k411;
    return nullptr;
}

// The IPTC records in Photoshop's image resource block, as APP13 carries them.
std::string photoshopBlock(const std::string& iptc) {
    std::string block("Photoshop 3.0\0" "8BIM\x04\x04\0\0\0\0", 24);
    block += char(uint8_t(iptc.size() >> 8));  // the 16-bit size OpenImageIO wrote
    block += char(uint8_t(iptc.size()));
    return block + iptc;
}

}  // namespace

ImageAttributes jpegAttributes(const ImageAttributes& attributes) {
    ImageAttributes result = attributes;
    for (const char* name : {"exif:XResolution", "exif:YResolution", "exif:ResolutionUnit"}) result.erase(name);
    if (sameName(result.getString("oiio:ColorSpace"), "sRGB")) result.set("Exif:ColorSpace", 1);
    return result;
}

// libjpeg's state, its destination and the sink; freed on every path.
struct JpegWriter::State {
    ErrorManager errors{};
    jpeg_compress_struct info{};
    jpeg_destination_mgr destination{};
    Sink sink;
    std::exception_ptr sink_failure;  // what the sink threw, to throw again past libjpeg
    bool created = false;
    bool failed = false;
    std::vector<uint8_t> output;   // libjpeg's output buffer
    std::vector<uint8_t> samples;  // a slice of rows as codes
    std::vector<JSAMPROW> row_pointers;
    size_t row_floats = 0;

    ~State() {
        if (created) jpeg_destroy_compress(&info);
    }

    // Passes libjpeg's bytes to the sink; false (the exception kept) if it threw.
    bool deliver(size_t size) {
        try {
            sink(output.data(), size);
            return true;
        } catch (...) {
            sink_failure = std::current_exception();
            return false;
        }
    }

    static State& of(j_compress_ptr info) { return *static_cast<State*>(info->client_data); }

    static void startDestination(j_compress_ptr info) {
        State& s = of(info);
        s.destination.next_output_byte = s.output.data();
        s.destination.free_in_buffer = s.output.size();
    }
    // The buffer is full. A failed sink jumps back to `run`, from a frame with nothing to destroy.
    static boolean emptyOutputBuffer(j_compress_ptr info) {
        State& s = of(info);
        if (!s.deliver(s.output.size())) std::longjmp(s.errors.jump, 1);
        startDestination(info);
        return TRUE;
    }
    static void termDestination(j_compress_ptr info) {
        State& s = of(info);
        if (!s.deliver(s.output.size() - s.destination.free_in_buffer)) std::longjmp(s.errors.jump, 1);
    }

    // Runs `step`, which calls into libjpeg and owns nothing to destroy: a libjpeg error or a
    // failed sink comes back here by longjmp and is thrown, once; the writer is then done.
    template <class Step>
    void run(const Step& step) {
        if (failed) throw std::logic_error("JpegWriter used after a failure");
        if (setjmp(errors.jump)) {
            failed = true;
            if (sink_failure) std::rethrow_exception(sink_failure);
            throw std::runtime_error(std::string("libjpeg: ") + errors.message);
        }
        step();
    }

    // One marker, if its data fit; else the reason goes to `left_out`.
    void writeMarker(int marker, const std::string& data, const char* what, std::vector<std::string>& left_out) {
        if (data.size() > kMaxMarkerData) {
            left_out.push_back(std::string(what) + " (" + std::to_string(data.size()) + " bytes, a JPEG marker holds " +
                               std::to_string(kMaxMarkerData) + ")");
            return;
        }
        run([&] { jpeg_write_marker(&info, marker, reinterpret_cast<const JOCTET*>(data.data()), unsigned(data.size())); });
    }
};

JpegWriter::JpegWriter(const JpegFormat& format, const JpegMetadata& metadata, Sink sink)
    : state_(std::make_unique<State>()) {
    if (format.channels != 1 && format.channels != 3) throw std::invalid_argument("JPEG holds grey or RGB images");
    if (format.width < 1 || format.height < 1 || format.width > JPEG_MAX_DIMENSION || format.height > JPEG_MAX_DIMENSION)
        throw std::invalid_argument("JPEG holds 1 to 65500 pixels a side");
    if (format.quality < 1 || format.quality > 100) throw std::invalid_argument("JPEG quality is 1 to 100");
    State& s = *state_;
    s.sink = std::move(sink);
    s.output.resize(kOutputBufferBytes);
    s.row_floats = size_t(format.width) * format.channels;
    s.info.err = jpeg_std_error(&s.errors.base);
    s.errors.base.error_exit = failHere;
    s.errors.base.emit_message = ignoreMessage;
    const ImageAttributes& attributes = metadata.attributes;
    const int* factors = format.channels == 3 ? subsamplingFactors(attributes.getString("jpeg:subsampling")) : nullptr;
    const bool progressive = attributes.getInt("jpeg:progressive") != 0;
    s.run([&] {
        jpeg_create_compress(&s.info);
        s.created = true;
        s.info.client_data = &s;
        s.destination.init_destination = State::startDestination;
        s.destination.empty_output_buffer = State::emptyOutputBuffer;
        s.destination.term_destination = State::termDestination;
        s.info.dest = &s.destination;
        s.info.image_width = format.width;
        s.info.image_height = format.height;
        s.info.input_components = int(format.channels);
        s.info.in_color_space = format.channels == 3 ? JCS_RGB : JCS_GRAYSCALE;
        jpeg_set_defaults(&s.info);
        setDensity(attributes, s.info);  // after the defaults, which reset it
        jpeg_set_quality(&s.info, format.quality, TRUE);
        if (factors) {
            jpeg_set_colorspace(&s.info, JCS_YCbCr);
            s.info.comp_info[0].h_samp_factor = factors[0];
            s.info.comp_info[0].v_samp_factor = factors[1];
            for (int c = 1; c < 3; ++c) s.info.comp_info[c].h_samp_factor = s.info.comp_info[c].v_samp_factor = 1;
        }
        if (progressive) jpeg_simple_progression(&s.info);
        jpeg_start_compress(&s.info, TRUE);
    });

    // The markers, in OpenImageIO's order. The comment keeps its terminating NUL.
    const std::string comment = attributes.getString("ImageDescription");
    if (!comment.empty()) s.writeMarker(JPEG_COM, std::string(comment.c_str(), comment.size() + 1), "the description", left_out_);
    s.writeMarker(JPEG_APP0 + 1, std::string("Exif\0\0", 6) + metadata.exif, "the EXIF data", left_out_);
    if (!metadata.iptc.empty()) s.writeMarker(JPEG_APP0 + 13, photoshopBlock(metadata.iptc), "the IPTC data", left_out_);
    if (!metadata.xmp.empty())
        s.writeMarker(JPEG_APP0 + 1, std::string("http://ns.adobe.com/xap/1.0/", 29) + metadata.xmp, "the XMP data", left_out_);
    const ImageAttribute* icc = attributes.find("ICCProfile");
    if (icc && !icc->bytes.empty()) {
        const std::vector<uint8_t>& profile = icc->bytes;
        const size_t count = (profile.size() + kIccChunkData - 1) / kIccChunkData;
        // OpenImageIO 2.4 copied the last of several chunks from the wrong place (the last
        // chunk's length times its index); the profile's true tail goes there instead.
        for (size_t i = 0; i < count; ++i) {
            std::string chunk("ICC_PROFILE", 12);
            chunk += char(uint8_t(i + 1));  // one byte each, as OpenImageIO wrote them
            chunk += char(uint8_t(count));
            const size_t begin = i * kIccChunkData, end = std::min(profile.size(), begin + kIccChunkData);
            chunk.append(reinterpret_cast<const char*>(profile.data()) + begin, end - begin);
            s.writeMarker(JPEG_APP0 + 2, chunk, "the ICC profile", left_out_);
        }
    }
}

JpegWriter::~JpegWriter() = default;

void JpegWriter::writeRows(const float* rows, uint32_t count) {
    State& s = *state_;
    if (s.info.next_scanline + count > s.info.image_height) throw std::logic_error("JpegWriter: rows past the image's height");
    const size_t row_bytes = s.row_floats;
    const uint32_t slice_rows = uint32_t(std::clamp<size_t>(kSliceBytes / row_bytes, 1, std::max(count, 1u)));
    s.samples.resize(size_t(slice_rows) * row_bytes);
    s.row_pointers.resize(slice_rows);
    for (uint32_t first = 0; first < count; first += slice_rows) {
        const uint32_t rows_here = std::min(slice_rows, count - first);
        parallelFor(rows_here, 16, [&](size_t begin, size_t end) {
            for (size_t y = begin; y < end; ++y)
                quantiseRow(rows + (first + y) * s.row_floats, s.samples.data() + y * row_bytes, s.row_floats);
        });
        for (uint32_t y = 0; y < rows_here; ++y) s.row_pointers[y] = s.samples.data() + y * row_bytes;
        s.run([&] {
            // A destination that never suspends takes every row.
            jpeg_write_scanlines(&s.info, s.row_pointers.data(), rows_here);
        });
    }
}

void JpegWriter::writeCodes(const uint8_t* codes, uint32_t count) {
    State& s = *state_;
    if (s.info.next_scanline + count > s.info.image_height) throw std::logic_error("JpegWriter: rows past the image's height");
    s.row_pointers.resize(count);
    for (uint32_t y = 0; y < count; ++y)  // libjpeg only reads them
        s.row_pointers[y] = const_cast<uint8_t*>(codes) + size_t(y) * s.row_floats;
    s.run([&] { jpeg_write_scanlines(&s.info, s.row_pointers.data(), count); });
}

void JpegWriter::finish() {
    State& s = *state_;
    if (s.info.next_scanline != s.info.image_height) throw std::logic_error("JpegWriter: rows missing");
    s.run([&] { jpeg_finish_compress(&s.info); });
}

}  // namespace ddt
