// ddtup's PNG writer: the parallel encoder's files decode bit-exactly with two independent
// decoders (libpng through OpenImageIO, and libspng) and pass pngcheck, whatever the layout,
// depth, size and number of pieces; their bytes do not depend on the thread count; they are no
// larger than zlib's level 6 without filtering (what vips writes); ImageWriter's samples and
// metadata chunks are those OpenImageIO 2.4's PNG writer wrote; a full disk leaves nothing.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <spng.h>
#include <stdlib.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "exif.h"
#include "image_file.h"
#include "parallel.h"
#include "png_encoder.h"
#include "oiio_metadata.h"
#include "png_metadata.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"

using ddt::PngEncoder;
using ddt::PngFormat;
using ddt::test::iccProfile;

namespace {

// Samples as a PNG stores them (16-bit big-endian), row after row.
struct Samples {
    PngFormat format;
    std::string bytes;
};

enum class Content {
    Noise,     // random bytes: incompressible, deflated by ISA-L
    Gradient,  // smooth ramps with a little noise, like a magnified photograph
    Drawing,   // rectangles of a few colours: flat pieces, deflated by zlib
};

Samples makeSamples(uint32_t width, uint32_t height, uint32_t channels, uint32_t bit_depth, Content content, uint32_t seed = 1) {
    Samples samples{{width, height, channels, bit_depth}, {}};
    samples.bytes.resize(samples.format.rowBytes() * height);
    std::mt19937 rng(seed);
    const uint32_t bytes_per_sample = bit_depth / 8;
    // The drawing's colours and its rectangles' corners, on a grid of 8 × 8 cells.
    std::vector<uint32_t> palette(4);
    for (uint32_t& colour : palette) colour = rng();
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (uint32_t c = 0; c < channels; ++c) {
                uint32_t value = 0;
                switch (content) {
                    case Content::Noise:
                        value = rng();
                        break;
                    case Content::Gradient:
                        value = uint32_t(std::lround((x * 7 + y * 5 + c * 40) * 0.4 * (bytes_per_sample == 2 ? 257 : 1))) + rng() % 3;
                        break;
                    case Content::Drawing:
                        value = palette[((x / 8) * 3 + (y / 8) * 5 + (x / 24) * (y / 24)) % 4] >> (c * 8);
                        value = value * (bytes_per_sample == 2 ? 257 : 1);
                        break;
                }
                char* at = &samples.bytes[((size_t(y) * width + x) * channels + c) * bytes_per_sample];
                if (bytes_per_sample == 2) {
                    at[0] = char(value >> 8);
                    at[1] = char(value);
                } else {
                    at[0] = char(value);
                }
            }
    return samples;
}

// Encodes into memory, the rows given in calls of 1, 2, 3, … rows (as ImageWriter's bands
// come, of any size).
std::string encode(const Samples& samples, const PngEncoder::Options& options = {}, const std::vector<ddt::PngChunk>& metadata = {},
                   PngEncoder::Statistics* statistics = nullptr) {
    std::string png;
    PngEncoder encoder(samples.format, metadata, [&](const uint8_t* data, size_t size) { png.append(reinterpret_cast<const char*>(data), size); },
                       options);
    const size_t row_bytes = samples.format.rowBytes();
    uint32_t y = 0;
    for (uint32_t count = 1; y < samples.format.height; ++count) {
        const uint32_t rows = std::min(count, samples.format.height - y);
        encoder.addRows(reinterpret_cast<const uint8_t*>(samples.bytes.data()) + y * row_bytes, rows);
        y += rows;
    }
    encoder.finish();
    if (statistics) *statistics = encoder.statistics();
    return png;
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream file(path, std::ios::binary);
    file << bytes;
    REQUIRE(file.good());
}

// The stored samples, through libpng (OpenImageIO's reader), asked not to premultiply.
Samples decodeWithOiio(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    REQUIRE(input);
    const OIIO::ImageSpec& spec = input->spec();
    const uint32_t depth = spec.format == OIIO::TypeDesc::UINT16 ? 16 : 8;
    Samples samples{{uint32_t(spec.width), uint32_t(spec.height), uint32_t(spec.nchannels), depth}, {}};
    samples.bytes.resize(samples.format.rowBytes() * samples.format.height);
    REQUIRE(input->read_image(0, 0, 0, spec.nchannels, spec.format, samples.bytes.data()));
    if (depth == 16)  // OpenImageIO gives the machine's byte order
        for (size_t i = 0; i < samples.bytes.size(); i += 2) {
            const uint16_t value = uint16_t(uint8_t(samples.bytes[i]) | uint8_t(samples.bytes[i + 1]) << 8);
            samples.bytes[i] = char(value >> 8);
            samples.bytes[i + 1] = char(value);
        }
    return samples;
}

// The stored samples, through libspng, which checks every CRC and the Adler-32 (SPNG_FMT_RAW:
// as stored, 16-bit big-endian).
Samples decodeWithSpng(const std::string& png) {
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> context(spng_ctx_new(0), spng_ctx_free);
    REQUIRE(context);
    REQUIRE(spng_set_png_buffer(context.get(), png.data(), png.size()) == 0);
    spng_ihdr header{};
    REQUIRE(spng_get_ihdr(context.get(), &header) == 0);
    const uint32_t channels[] = {1, 0, 3, 0, 2, 0, 4};
    REQUIRE(header.color_type <= 6);
    Samples samples{{header.width, header.height, channels[header.color_type], header.bit_depth}, {}};
    size_t size = 0;
    REQUIRE(spng_decoded_image_size(context.get(), SPNG_FMT_RAW, &size) == 0);
    samples.bytes.resize(size);
    const int error = spng_decode_image(context.get(), samples.bytes.data(), size, SPNG_FMT_RAW, 0);
    INFO("libspng: " << spng_strerror(error));
    REQUIRE(error == 0);
    return samples;
}

// "" when pngcheck finds nothing wrong, else what it says.
std::string pngcheckProblems(const std::string& path) {
    const Run run = runShell("pngcheck -q " + shellQuoted(path));
    return run.exit_code == 0 ? "" : run.out + run.err;
}

void requireSameSamples(const Samples& decoded, const Samples& expected) {
    REQUIRE(decoded.format.width == expected.format.width);
    REQUIRE(decoded.format.height == expected.format.height);
    REQUIRE(decoded.format.channels == expected.format.channels);
    REQUIRE(decoded.format.bit_depth == expected.format.bit_depth);
    REQUIRE(decoded.bytes.size() == expected.bytes.size());
    const auto mismatch = std::mismatch(decoded.bytes.begin(), decoded.bytes.end(), expected.bytes.begin());
    const size_t at = size_t(mismatch.first - decoded.bytes.begin());
    INFO("first different byte: " << at << " of " << decoded.bytes.size() << ": " << int(uint8_t(decoded.bytes[at])) << " instead of "
                                  << int(uint8_t(expected.bytes[at])));
    REQUIRE(mismatch.first == decoded.bytes.end());
}

// The file passes pngcheck and both decoders give back exactly `samples`.
void requireDecodesExactly(const std::string& png, const Samples& samples, const TempFolder& folder) {
    const std::string path = folder / "decoded.png";
    writeBytes(path, png);
    CHECK(pngcheckProblems(path) == "");
    requireSameSamples(decodeWithOiio(path), samples);
    requireSameSamples(decodeWithSpng(png), samples);
}

// Sets the pool's thread count for one scope.
class ThreadCount {
public:
    explicit ThreadCount(unsigned count) : saved_(ddt::threadCount()) { ddt::setThreadCount(count); }
    ~ThreadCount() { ddt::setThreadCount(saved_); }
    ThreadCount(const ThreadCount&) = delete;
    ThreadCount& operator=(const ThreadCount&) = delete;

private:
    unsigned saved_;
};

// A PNG's chunks in order.
std::vector<ddt::PngChunk> chunksOf(const std::string& png) {
    std::vector<ddt::PngChunk> chunks;
    for (size_t at = 8; at + 12 <= png.size();) {
        const uint32_t length = uint32_t(uint8_t(png[at])) << 24 | uint32_t(uint8_t(png[at + 1])) << 16 |
                                uint32_t(uint8_t(png[at + 2])) << 8 | uint8_t(png[at + 3]);
        chunks.push_back({png.substr(at + 4, 4), png.substr(at + 8, length)});
        at += 12 + size_t(length);
    }
    return chunks;
}

// A PNG's chunks in order, IHDR, IDAT and IEND left out.
std::vector<ddt::PngChunk> metadataChunks(const std::string& png) {
    std::vector<ddt::PngChunk> chunks;
    for (ddt::PngChunk& chunk : chunksOf(png))
        if (chunk.type != "IHDR" && chunk.type != "IDAT" && chunk.type != "IEND") chunks.push_back(std::move(chunk));
    return chunks;
}

// ddtup's metadata chunks of what an OpenImageIO spec holds (its attributes and offset).
ddt::PngMetadata pngMetadataOf(const OIIO::ImageSpec& spec) {
    ddt::PngMetadataSource source;
    source.attributes = ddt::attributesOf(spec);
    source.channels = uint32_t(spec.nchannels);
    source.x_offset = spec.x;
    source.y_offset = spec.y;
    source.exif = ddt::encodeExif(source.attributes);
    return ddt::pngMetadata(source);
}

// The filter type byte of each row, from the inflated image data.
std::vector<uint8_t> rowFilters(const std::string& png, const PngFormat& format) {
    std::string stream;
    for (const ddt::PngChunk& chunk : chunksOf(png))
        if (chunk.type == "IDAT") stream += chunk.data;
    const size_t stride = format.rowBytes() + 1;
    std::string data(stride * format.height, '\0');
    uLongf size = data.size();
    REQUIRE(uncompress(reinterpret_cast<Bytef*>(data.data()), &size, reinterpret_cast<const Bytef*>(stream.data()),
                       uLong(stream.size())) == Z_OK);
    REQUIRE(size == data.size());
    std::vector<uint8_t> filters;
    for (size_t y = 0; y < format.height; ++y) filters.push_back(uint8_t(data[y * stride]));
    return filters;
}

// An iCCP chunk's data with its profile inflated: zlib streams of one profile may differ.
std::string inflatedIcc(const std::string& data) {
    const size_t name_end = data.find('\0');
    REQUIRE(name_end != std::string::npos);
    std::string profile(1 << 20, '\0');
    uLongf size = profile.size();
    REQUIRE(uncompress(reinterpret_cast<Bytef*>(profile.data()), &size, reinterpret_cast<const Bytef*>(data.data()) + name_end + 2,
                       uLong(data.size() - name_end - 2)) == Z_OK);
    return data.substr(0, name_end + 2) + profile.substr(0, size);
}

void setIcc(OIIO::ImageSpec& spec, const std::string& profile) {
    spec.attribute("ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, int(profile.size())), profile.data());
}

// Writes a small image with OpenImageIO's own writer.
void writeWithOiio(const std::string& path, const OIIO::ImageSpec& spec, const std::vector<float>& pixels) {
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());
}

// Sets an environment variable for one scope.
class ScopedVariable {
public:
    ScopedVariable(const char* name, const std::string& value) : name_(name) { ::setenv(name, value.c_str(), 1); }
    ~ScopedVariable() { ::unsetenv(name_); }
    ScopedVariable(const ScopedVariable&) = delete;
    ScopedVariable& operator=(const ScopedVariable&) = delete;

private:
    const char* name_;
};

ddt::Image noiseImage(uint32_t width, uint32_t height, uint32_t channels) {
    ddt::Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    std::mt19937 rng(5);
    image.pixels.resize(size_t(width) * height * channels);
    for (float& value : image.pixels) value = float(rng() % 256) * (1.0f / 255.0f);
    return image;
}

}  // namespace

TEST_CASE("png: every layout, depth and shape decodes bit-exactly with libpng and libspng and passes pngcheck") {
    TempFolder folder;
    const std::pair<uint32_t, uint32_t> sizes[] = {{1, 1}, {1, 37}, {37, 1}, {17, 13}, {255, 9}};
    for (uint32_t channels = 1; channels <= 4; ++channels)
        for (uint32_t depth : {8u, 16u})
            for (const auto& [width, height] : sizes)
                for (Content content : {Content::Noise, Content::Gradient, Content::Drawing}) {
                    INFO(width << "×" << height << ", " << channels << " channels, " << depth << "-bit, content " << int(content));
                    const Samples samples = makeSamples(width, height, channels, depth, content);
                    requireDecodesExactly(encode(samples), samples, folder);
                }
}

// Pieces of a few rows: many batches and, on the drawing, flat pieces stored unfiltered next to
// busy ones stored filtered, so that some are deflated again against the real dictionary.
TEST_CASE("png: an image of many pieces, flat and busy, decodes exactly") {
    TempFolder folder;
    ThreadCount threads(2);
    PngEncoder::Options options;
    options.chunk_bytes = 2000;
    for (uint32_t depth : {8u, 16u})
        for (uint32_t channels : {1u, 3u, 4u}) {
            INFO(channels << " channels, " << depth << "-bit");
            // Bands of drawing, noise, drawing and gradient, 37 rows each: their edges fall
            // inside batches of pieces as well as between them.
            Samples samples = makeSamples(97, 600, channels, depth, Content::Drawing);
            const Samples noise = makeSamples(97, 600, channels, depth, Content::Noise);
            const Samples gradient = makeSamples(97, 600, channels, depth, Content::Gradient);
            const size_t row_bytes = samples.format.rowBytes();
            for (uint32_t y = 0; y < 600; ++y) {
                const Samples* band[] = {&samples, &noise, &samples, &gradient};
                samples.bytes.replace(y * row_bytes, row_bytes, band[(y / 37) % 4]->bytes, y * row_bytes, row_bytes);
            }
            PngEncoder::Statistics statistics;
            const std::string png = encode(samples, options, {}, &statistics);
            requireDecodesExactly(png, samples, folder);
            CHECK(statistics.pieces > 20);
            CHECK(statistics.flat > 0);
            CHECK(statistics.flat < statistics.pieces);
            CHECK(statistics.unfiltered > 0);
            CHECK(statistics.deflated_again > 0);
        }
}

// Rows that one filter each makes nearly zero: the top half repeats one ramp (Up: all zeros
// below its first row), each row of the bottom half is one value, 5 above the row before
// (Paeth: the first byte 5, from above, then zeros, from the left). Per row the heuristic takes
// Up in the top half and Paeth in the bottom; once per piece it must take one filter for all
// of the piece's rows.
TEST_CASE("png: the adaptive filter chosen per piece is one type for all of a piece's rows") {
    TempFolder folder;
    Samples samples{{64, 40, 1, 8}, {}};
    for (uint32_t y = 0; y < 40; ++y)
        for (uint32_t x = 0; x < 64; ++x) samples.bytes += char(y < 20 ? x * 3 : y * 5);
    PngEncoder::Options options;
    options.zlib_for_flat = options.try_unfiltered = false;  // the filtered rows are stored
    options.filter = ddt::PngFilter::Adaptive;
    const std::vector<uint8_t> per_row = rowFilters(encode(samples, options), samples.format);
    CHECK(per_row[1] == uint8_t(ddt::PngFilter::Up));
    CHECK(per_row.back() == uint8_t(ddt::PngFilter::Paeth));
    options.filter = ddt::PngFilter::PieceAdaptive;
    for (size_t chunk_bytes : {size_t(1) << 18, size_t(65 * 10)}) {  // one piece; pieces of 10 rows
        INFO("pieces of " << chunk_bytes << " bytes");
        options.chunk_bytes = chunk_bytes;
        const std::string png = encode(samples, options);
        requireDecodesExactly(png, samples, folder);
        const std::vector<uint8_t> per_piece = rowFilters(png, samples.format);
        const size_t rows = std::min<size_t>(40, chunk_bytes / 65);
        for (size_t y = 0; y < per_piece.size(); ++y) {
            INFO("row " << y);
            CHECK(per_piece[y] == per_piece[y / rows * rows]);
            CHECK(per_piece[y] < 5);
        }
        if (rows == 10) {  // rows 10-19 and 30-39 are pieces within one half: that half's filter
            CHECK(per_piece[10] == uint8_t(ddt::PngFilter::Up));
            CHECK(per_piece.back() == uint8_t(ddt::PngFilter::Paeth));
        }
    }
}

TEST_CASE("png: the bytes do not depend on the number of threads") {
    const Samples samples = makeSamples(131, 700, 3, 8, Content::Gradient);
    PngEncoder::Options options;
    options.chunk_bytes = 5000;  // several batches whatever the thread count
    std::string one, two, three;
    {
        ThreadCount threads(1);
        one = encode(samples, options);
    }
    {
        ThreadCount threads(2);
        two = encode(samples, options);
    }
    {
        ThreadCount threads(3);
        three = encode(samples, options);
    }
    CHECK(one == two);
    CHECK(one == three);
}

// Only a batch of pieces is held: nearly all of a tall image is out before finish().
TEST_CASE("png: rows are written as they arrive, and the memory held does not grow with the height") {
    ThreadCount threads(2);
    const Samples samples = makeSamples(64, 4000, 3, 8, Content::Noise);
    PngEncoder::Options options;
    options.chunk_bytes = 4096;  // 21 rows a piece, 4 pieces a batch on 2 threads
    size_t written = 0;
    PngEncoder encoder(samples.format, {}, [&](const uint8_t*, size_t size) { written += size; }, options);
    encoder.addRows(reinterpret_cast<const uint8_t*>(samples.bytes.data()), samples.format.height);
    const size_t before_finish = written;
    encoder.finish();
    // Noise does not compress: the file is about the samples' size, and all but the last
    // batch (84 of 4000 rows) is out before finish().
    CHECK(before_finish > written * 95 / 100);
    CHECK(before_finish < written);
}

// vips writes zlib's level 6 without filtering; the comparison adds only the smallest PNG's
// other bytes (signature, IHDR, one IDAT's frame, IEND: 57), though vips' file has more. Noise
// about mid-grey is where filtering hurts: the difference of two noisy samples is noisier.
TEST_CASE("png: no larger than zlib's level 6 without filtering, on a photograph, a drawing and noise") {
    const Samples drawing = makeSamples(640, 480, 3, 8, Content::Drawing);
    Samples noise{{512, 512, 3, 8}, std::string(512 * 512 * 3, '\0')};
    std::mt19937 rng(9);
    std::normal_distribution<float> grain(128.0f, 20.0f);
    for (char& sample : noise.bytes) sample = char(std::clamp(std::lround(grain(rng)), 0L, 255L));
    const ddt::Image photo = ddt::readImage(std::string(DDTUP_TEST_DATA) + "/../../bench/data/real/astronaut.png");
    Samples photograph{{photo.width, photo.height, photo.channels, 8}, std::string(photo.pixels.size(), '\0')};
    OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, photo.pixels.data(), OIIO::TypeDesc::UINT8, photograph.bytes.data(),
                               int(photo.pixels.size()));
    for (const Samples* samples : std::initializer_list<const Samples*>{&drawing, &photograph, &noise}) {
        std::string unfiltered;
        const size_t row_bytes = samples->format.rowBytes();
        for (uint32_t y = 0; y < samples->format.height; ++y) unfiltered += '\0' + samples->bytes.substr(y * row_bytes, row_bytes);
        std::string zlib(compressBound(uLong(unfiltered.size())), '\0');
        uLongf zlib_size = zlib.size();
        REQUIRE(compress2(reinterpret_cast<Bytef*>(zlib.data()), &zlib_size, reinterpret_cast<const Bytef*>(unfiltered.data()),
                          uLong(unfiltered.size()), 6) == Z_OK);
        const std::string png = encode(*samples);
        INFO(samples->format.width << "×" << samples->format.height << ": " << png.size() << " bytes, zlib " << zlib_size);
        CHECK(png.size() <= zlib_size + 57);
    }
}

TEST_CASE("png: rows past the height, and a finish before the last row, are refused") {
    const Samples samples = makeSamples(5, 4, 3, 8, Content::Noise);
    PngEncoder encoder(samples.format, {}, [](const uint8_t*, size_t) {});
    const auto* rows = reinterpret_cast<const uint8_t*>(samples.bytes.data());
    encoder.addRows(rows, 3);
    CHECK_THROWS_AS(encoder.finish(), std::logic_error);
    CHECK_THROWS_AS(encoder.addRows(rows, 2), std::logic_error);
    encoder.addRows(rows, 1);
    CHECK_NOTHROW(encoder.finish());
    CHECK_THROWS_AS(encoder.addRows(rows, 1), std::logic_error);
    CHECK_THROWS_AS(PngEncoder({5, 4, 5, 8}, {}, [](const uint8_t*, size_t) {}), std::invalid_argument);
    CHECK_THROWS_AS(PngEncoder({5, 4, 3, 12}, {}, [](const uint8_t*, size_t) {}), std::invalid_argument);
    CHECK_THROWS_AS(PngEncoder({0, 4, 3, 8}, {}, [](const uint8_t*, size_t) {}), std::invalid_argument);
}

// Values on either side of the 8 and 16-bit rounding points, below 0 and above 1, in rows whose
// length is not a multiple of 4 (OpenImageIO converts 4 values at a time, the rest otherwise):
// ImageWriter's samples are the ones OpenImageIO's PNG writer made of the same floats.
TEST_CASE("png: float samples become the 8 and 16-bit samples OpenImageIO's writer made of them") {
    TempFolder folder;
    std::vector<float> values = {-1.0f, -0.0f, 0.0f, 1.0f, 1.5f, 1e-9f, 0.999999f};
    for (uint32_t k = 0; k < 256; ++k)
        for (float offset : {-1e-6f, 0.0f, 1e-6f}) {
            values.push_back(float(k) / 255.0f + offset);
            values.push_back((float(k) + 0.5f) / 255.0f + offset);
            values.push_back((float(k * 257) + 0.5f) / 65535.0f + offset);
        }
    for (ddt::SampleType type : {ddt::SampleType::UInt8, ddt::SampleType::UInt16})
        for (uint32_t channels : {1u, 3u, 4u}) {
            INFO(channels << " channels, " << ddt::sampleTypeName(type));
            ddt::Image image;
            image.width = 13;  // 13, 39 or 52 values a row: 1, 3 and 0 left after groups of 4
            image.height = uint32_t(values.size() / (13 * channels)) + 1;
            image.channels = channels;
            image.sample_type = type;
            image.pixels.resize(size_t(image.width) * image.height * channels);
            for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = values[i % values.size()];
            if (channels == 4)  // opaque, so that no colour is divided by alpha
                for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
            ddt::writeImage(folder / "ours.png", image);
            OIIO::ImageSpec spec(int(image.width), int(image.height), int(channels),
                                 type == ddt::SampleType::UInt8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
            if (channels == 4) {
                spec.alpha_channel = 3;
                spec.attribute("oiio:UnassociatedAlpha", 1);  // as ImageWriter opened it
            }
            writeWithOiio(folder / "theirs.png", spec, image.pixels);
            requireSameSamples(decodeWithOiio(folder / "ours.png"), decodeWithOiio(folder / "theirs.png"));
        }
}

// OpenImageIO 2.4's PNG writer is the reference: the same spec gives the same chunks, in the
// same order (the ICC profile compared inflated; eXIf is ddtup's addition).
TEST_CASE("png: the metadata chunks are the ones OpenImageIO 2.4's writer wrote, chunk for chunk") {
    TempFolder folder;
    std::vector<std::pair<std::string, OIIO::ImageSpec>> specs;
    auto add = [&](const std::string& name, uint32_t channels, const std::function<void(OIIO::ImageSpec&)>& set) {
        OIIO::ImageSpec spec(4, 2, int(channels), OIIO::TypeDesc::UINT8);
        set(spec);
        specs.emplace_back(name, spec);
    };
    add("nothing", 3, [](OIIO::ImageSpec&) {});
    add("sRGB", 3, [](OIIO::ImageSpec& s) { s.attribute("oiio:ColorSpace", "sRGB"); });
    add("linear", 3, [](OIIO::ImageSpec& s) { s.attribute("oiio:ColorSpace", "Linear"); });
    add("gamma 2.2", 3, [](OIIO::ImageSpec& s) { s.attribute("oiio:ColorSpace", "Gamma2.2"); });
    add("gamma 1.8", 1, [](OIIO::ImageSpec& s) {
        s.attribute("oiio:ColorSpace", "Gamma1.8");
        s.attribute("oiio:Gamma", 1.8f);
    });
    add("gamma from oiio:Gamma", 3, [](OIIO::ImageSpec& s) {
        s.attribute("oiio:ColorSpace", "Gamma");
        s.attribute("oiio:Gamma", 2.5f);
    });
    add("another colour space", 3, [](OIIO::ImageSpec& s) { s.attribute("oiio:ColorSpace", "ACEScg"); });
    add("dots per inch", 3, [](OIIO::ImageSpec& s) {
        s.attribute("XResolution", 216.0f);
        s.attribute("YResolution", 300.0f);
        s.attribute("ResolutionUnit", "in");
    });
    add("dots per centimetre", 3, [](OIIO::ImageSpec& s) {
        s.attribute("XResolution", 300.0f);
        s.attribute("YResolution", 150.0f);
        s.attribute("ResolutionUnit", "cm");
    });
    add("resolution without unit", 3, [](OIIO::ImageSpec& s) { s.attribute("XResolution", 300.0f); });
    add("aspect ratio", 3, [](OIIO::ImageSpec& s) { s.attribute("PixelAspectRatio", 2.0f); });
    add("aspect ratio and resolution", 3, [](OIIO::ImageSpec& s) {
        s.attribute("YResolution", 72.0f);
        s.attribute("PixelAspectRatio", 0.5f);
        s.attribute("ResolutionUnit", "inch");
    });
    add("unit alone", 3, [](OIIO::ImageSpec& s) { s.attribute("ResolutionUnit", "none"); });
    add("date", 3, [](OIIO::ImageSpec& s) { s.attribute("DateTime", "2023:04:05 06:07:08"); });
    add("date with dashes", 3, [](OIIO::ImageSpec& s) { s.attribute("DateTime", "1999-12-31 23:59:59"); });
    add("not a date", 3, [](OIIO::ImageSpec& s) { s.attribute("DateTime", "yesterday"); });
    add("month 13", 3, [](OIIO::ImageSpec& s) { s.attribute("DateTime", "2023:13:05 06:07:08"); });
    add("text", 4, [](OIIO::ImageSpec& s) {
        s.attribute("ImageDescription", "a description");
        s.attribute("Artist", "an artist");
        s.attribute("DocumentName", "a title");
        s.attribute("Copyright", "(c) nobody");
        s.attribute("Software", "ddtup");
        s.attribute("Exif:LensModel", "a lens");
        s.attribute("Exif:FocalLength", 50.0f);  // not text
        s.attribute("name", "another title");
        s.attribute("description", "another description");
        s.attribute("compression", "zip");
        s.attribute("planarconfig", "contig");
        s.attribute("  spaced   key ", "spaces");
        s.attribute("k\xe9y", "Latin-1 key");
        s.attribute("utf", "h\xc3\xa9llo");
        s.attribute("empty", "");
        s.attribute(std::string(90, 'k'), "a long key");
    });
    add("offset", 3, [](OIIO::ImageSpec& s) {
        s.x = 5;
        s.y = -3;
    });
    add("ICC profile", 3, [](OIIO::ImageSpec& s) { setIcc(s, iccProfile("RGB ")); });
    add("ICC profile and sRGB", 4, [](OIIO::ImageSpec& s) {
        s.attribute("oiio:ColorSpace", "sRGB");
        setIcc(s, iccProfile("RGB "));
    });
    add("ICC profile and gamma", 3, [](OIIO::ImageSpec& s) {
        s.attribute("oiio:ColorSpace", "Gamma2.2");
        setIcc(s, iccProfile("RGB "));
    });
    add("grey ICC profile", 2, [](OIIO::ImageSpec& s) { setIcc(s, iccProfile("GRAY")); });

    for (const auto& [name, spec] : specs) {
        INFO(name);
        const std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels, 0.5f);
        writeWithOiio(folder / "theirs.png", spec, pixels);
        std::vector<ddt::PngChunk> theirs = metadataChunks(readFile(folder / "theirs.png"));
        ddt::PngMetadata ours = pngMetadataOf(spec);
        CHECK(ours.left_out.empty());
        std::erase_if(ours.chunks, [](const ddt::PngChunk& chunk) { return chunk.type == "eXIf"; });
        REQUIRE(ours.chunks.size() == theirs.size());
        for (size_t i = 0; i < theirs.size(); ++i) {
            INFO("chunk " << i << ": " << theirs[i].type);
            CHECK(ours.chunks[i].type == theirs[i].type);
            if (theirs[i].type == "iCCP") CHECK(inflatedIcc(ours.chunks[i].data) == inflatedIcc(theirs[i].data));
            else CHECK(ours.chunks[i].data == theirs[i].data);
        }
    }
}

// Where libpng refused the spec and OpenImageIO then wrote no file, that piece of metadata
// is left out, with a note.
TEST_CASE("png: metadata that PNG cannot carry is left out with a note, and the image is written") {
    TempFolder folder;
    OIIO::ImageSpec spec(4, 2, 1, OIIO::TypeDesc::UINT8);
    setIcc(spec, iccProfile("RGB "));  // for colour, on a grey image
    writeWithOiio(folder / "in.tif", spec, std::vector<float>(8, 0.5f));
    const ddt::Image image = ddt::readImage(folder / "in.tif");
    REQUIRE(image.channels == 1);
    const std::vector<std::string> notes = ddt::writeImage(folder / "out.png", image);
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::StartsWith(folder / "out.png: the ICC profile") && Catch::Contains("grey") &&
                             Catch::EndsWith("is left out"));
    CHECK(pngcheckProblems(folder / "out.png") == "");
    auto input = OIIO::ImageInput::open(folder / "out.png");
    REQUIRE(input);
    CHECK(input->spec().find_attribute("ICCProfile") == nullptr);

    // A profile that is not whole, and a text key with nothing libpng keeps.
    OIIO::ImageSpec grey(4, 2, 1, OIIO::TypeDesc::UINT8);
    std::string damaged = iccProfile("GRAY");
    damaged.resize(100);
    setIcc(grey, damaged);
    grey.attribute("\x01\x02", "a key without letters");
    const std::vector<std::string> left_out = pngMetadataOf(grey).left_out;
    REQUIRE(left_out.size() == 2);
    CHECK(left_out[0] == "the ICC profile (damaged)");
    CHECK_THAT(left_out[1], Catch::StartsWith("the text attribute"));
}

TEST_CASE("png: ICC profile, EXIF, XMP, text, date and resolution survive a magnification") {
    TempFolder folder;
    // Everything but XMP from a TIFF, written by OpenImageIO.
    OIIO::ImageSpec spec(6, 4, 3, OIIO::TypeDesc::UINT8);
    const std::string profile = iccProfile("RGB ");
    setIcc(spec, profile);
    spec.attribute("Exif:FocalLength", 50.0f);
    spec.attribute("Exif:Flash", 1);
    spec.attribute("Exif:LensModel", "a lens");
    spec.attribute("ImageDescription", "a test card");
    spec.attribute("Artist", "ddtup tests");
    spec.attribute("Copyright", "(c) nobody");
    spec.attribute("DateTime", "2021:02:03 04:05:06");
    spec.attribute("XResolution", 72.0f);
    spec.attribute("YResolution", 72.0f);
    spec.attribute("ResolutionUnit", "in");
    writeWithOiio(folder / "in.tif", spec, std::vector<float>(6 * 4 * 3, 0.5f));
    // XMP from a PNG's text chunk: what OpenImageIO reads of it (2.4 skips properties written
    // as attributes of rdf:Description, so they are elements here).
    OIIO::ImageSpec xmp_spec(6, 4, 3, OIIO::TypeDesc::UINT8);
    xmp_spec.attribute("XML:com.adobe.xmp",
                       "<?xpacket begin=\"\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?><x:xmpmeta xmlns:x=\"adobe:ns:meta/\">"
                       "<rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"><rdf:Description rdf:about=\"\" "
                       "xmlns:photoshop=\"http://ns.adobe.com/photoshop/1.0/\"><photoshop:City>Leuven</photoshop:City>"
                       "<photoshop:Headline>a headline</photoshop:Headline></rdf:Description></rdf:RDF></x:xmpmeta>"
                       "<?xpacket end=\"w\"?>");
    writeWithOiio(folder / "xmp.png", xmp_spec, std::vector<float>(6 * 4 * 3, 0.5f));

    for (const char* input : {"in.tif", "xmp.png"}) {
        INFO(input);
        const ddt::Image image = ddt::readImage(folder / input);
        ddt::ImageWriter writer(folder / "out.png", 12, 8, image);  // magnified 2×
        writer.writeRows(0, 8, std::vector<float>(12 * 8 * 3, 0.25f).data());
        writer.commit();
        CHECK(writer.notes().empty());
        CHECK(pngcheckProblems(folder / "out.png") == "");
        auto back = OIIO::ImageInput::open(folder / "out.png");
        REQUIRE(back);
        const OIIO::ImageSpec& written = back->spec();
        if (std::string(input) == "xmp.png") {
            CHECK(written.get_string_attribute("IPTC:City") == "Leuven");
            CHECK(written.get_string_attribute("IPTC:Headline") == "a headline");
            continue;
        }
        const OIIO::ParamValue* icc = written.find_attribute("ICCProfile");
        REQUIRE(icc);
        CHECK(std::string(static_cast<const char*>(icc->data()), icc->type().size()) == profile);
        CHECK(written.get_float_attribute("Exif:FocalLength") == 50.0f);
        CHECK(written.get_int_attribute("Exif:Flash") == 1);
        CHECK(written.get_string_attribute("Exif:LensModel") == "a lens");
        CHECK(written.get_string_attribute("ImageDescription") == "a test card");
        CHECK(written.get_string_attribute("Artist") == "ddtup tests");
        CHECK(written.get_string_attribute("Copyright") == "(c) nobody");
        CHECK(written.get_string_attribute("DateTime") == "2021:02:03 04:05:06");
        // Twice the dots per inch. pHYs holds whole pixels per metre (5669 for 144 dpi is
        // 143.99 dpi): a thousandth allows for that truncation.
        CHECK(written.get_float_attribute("XResolution") == Approx(144.0f).epsilon(1e-3));
        CHECK(written.get_float_attribute("YResolution") == Approx(144.0f).epsilon(1e-3));
    }
}

// Through the writer's test hook (DDTUP_TEST_WRITE_LIMIT: a write past that many bytes fails
// with ENOSPC), past the header, in the image data.
TEST_CASE("png: a disk that fills up in the middle of the image data is one error, and no file stays") {
    TempFolder folder;
    const ddt::Image image = noiseImage(200, 200, 3);
    ddt::writeImage(folder / "whole.png", image);
    const size_t whole = std::filesystem::file_size(folder / "whole.png");
    std::filesystem::remove(folder / "whole.png");
    const size_t limit = 20000;
    REQUIRE(whole > 2 * limit);  // the failure comes in the image data, not in the header
    ScopedVariable variable("DDTUP_TEST_WRITE_LIMIT", std::to_string(limit));
    {
        ddt::ImageWriter writer(folder / "full.png", 200, 200, image);
        bool failed = false;
        for (uint32_t y = 0; y < 200 && !failed; y += 10) {
            try {
                writer.writeRows(y, y + 10, image.row(y));
            } catch (const ddt::UserError& error) {
                CHECK(std::string(error.what()) == folder / "full.png" + ": No space left on device");
                failed = true;
            }
        }
        if (!failed) CHECK_THROWS_WITH(writer.commit(), folder / "full.png" + ": No space left on device");
    }
    CHECK(folder.names().empty());
}
