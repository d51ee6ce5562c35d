// ddtup_bench_png IMAGE...: how long PNG writing takes and how large the files come out, for
// the choices core/io/png_encoder.cpp documents: the filter, ISA-L's level, the chunk size,
// against zlib (level 6 without filtering is what `vips copy x.png y.png` writes) and against
// OpenImageIO's PNG writer that ddtup used before. Times are the best of a few runs, on the
// threads --threads allows (default: all). Not run by ctest.
#include <OpenImageIO/imageio.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "image_file.h"
#include "parallel.h"
#include "png_encoder.h"

namespace {

using Clock = std::chrono::steady_clock;

double processSeconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

// Wall and processor seconds, the best of `runs` runs of `work` each. The machine may be
// shared: the processor time, all threads together, is the steadier measure of work.
struct Timing {
    double wall = 1e30, cpu = 1e30;
};

Timing bestTime(int runs, const std::function<void()>& work) {
    Timing best;
    for (int i = 0; i < runs; ++i) {
        const auto start = Clock::now();
        const double cpu_start = processSeconds();
        work();
        best.cpu = std::min(best.cpu, processSeconds() - cpu_start);
        best.wall = std::min(best.wall, std::chrono::duration<double>(Clock::now() - start).count());
    }
    return best;
}

const char* filterName(ddt::PngFilter filter) {
    static const char* names[] = {"none", "sub", "up", "average", "paeth", "adaptive", "adaptive per piece"};
    return names[int(filter)];
}

struct Samples {
    ddt::PngFormat format;
    std::vector<uint8_t> native;  // in the machine's byte order, for OpenImageIO
    std::vector<uint8_t> bytes;   // as the file stores them
};

// The samples as the file stores them (straight alpha), read with OpenImageIO.
Samples storedSamples(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    if (!input) throw std::runtime_error(path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    Samples samples;
    samples.format = {uint32_t(spec.width), uint32_t(spec.height), uint32_t(spec.nchannels), spec.format == OIIO::TypeDesc::UINT16 ? 16u : 8u};
    samples.bytes.resize(samples.format.rowBytes() * samples.format.height);
    const OIIO::TypeDesc type = samples.format.bit_depth == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    if (!input->read_image(0, 0, 0, spec.nchannels, type, samples.bytes.data())) throw std::runtime_error(path + ": " + input->geterror());
    samples.native = samples.bytes;
    if (samples.format.bit_depth == 16)
        for (size_t i = 0; i < samples.bytes.size(); i += 2) std::swap(samples.bytes[i], samples.bytes[i + 1]);
    return samples;
}

struct Encoding {
    size_t size = 0;
    Timing time;
    ddt::PngEncoder::Statistics statistics;
};

// The PNG's size and the best time to encode it into memory.
Encoding encode(const Samples& samples, const ddt::PngEncoder::Options& options, int runs) {
    std::vector<uint8_t> out;
    out.reserve(samples.bytes.size() + samples.bytes.size() / 8);
    Encoding result;
    result.time = bestTime(runs, [&] {
        out.clear();
        ddt::PngEncoder encoder(samples.format, {}, [&](const uint8_t* data, size_t size) { out.insert(out.end(), data, data + size); },
                                options);
        encoder.addRows(samples.bytes.data(), samples.format.height);
        encoder.finish();
        result.statistics = encoder.statistics();
    });
    result.size = out.size();
    return result;
}

// The image data as an unfiltered PNG holds it: each row after a filter byte 0 (none).
std::vector<uint8_t> unfiltered(const Samples& samples) {
    std::vector<uint8_t> stream;
    const size_t row = samples.format.rowBytes();
    for (uint32_t y = 0; y < samples.format.height; ++y) {
        stream.push_back(0);
        stream.insert(stream.end(), samples.bytes.begin() + ptrdiff_t(y * row), samples.bytes.begin() + ptrdiff_t((y + 1) * row));
    }
    return stream;
}

std::pair<size_t, Timing> zlibSize(const std::vector<uint8_t>& stream, int level, int runs) {
    std::vector<uint8_t> out(compressBound(stream.size()));
    uLongf size = 0;
    const Timing seconds = bestTime(runs, [&] {
        size = out.size();
        compress2(out.data(), &size, stream.data(), stream.size(), level);
    });
    return {size, seconds};
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> images;
    int runs = 3;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--threads" && i + 1 < argc) ddt::setThreadCount(unsigned(std::atoi(argv[++i])));
        else if (arg == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
        else images.push_back(arg);
    }
    if (images.empty()) {
        std::fprintf(stderr, "usage: ddtup_bench_png [--threads N] [--runs N] IMAGE...\n");
        return 2;
    }
    OIIO::attribute("threads", int(ddt::threadCount()));
    const std::string temp = (std::filesystem::temp_directory_path() / "ddtup_bench_png.png").string();
    for (const std::string& path : images) {
        const ddt::Image image = ddt::readImage(path);
        const Samples samples = storedSamples(path);
        std::printf("%s: %u x %u, %u channels, %u-bit, %u threads\n", path.c_str(), image.width, image.height, image.channels,
                    samples.format.bit_depth, ddt::threadCount());

        const auto [vips_size, vips_time] = zlibSize(unfiltered(samples), 6, 1);
        std::printf("  %-36s %10zu bytes  %7.3f s wall %7.3f s cpu\n", "zlib 6, no filter (vips)", vips_size, vips_time.wall, vips_time.cpu);
        const auto [zlib1_size, zlib1_time] = zlibSize(unfiltered(samples), 1, 1);
        std::printf("  %-36s %10zu bytes  %7.3f s wall %7.3f s cpu\n", "zlib 1, no filter", zlib1_size, zlib1_time.wall, zlib1_time.cpu);

        auto row = [&](const std::string& name, const ddt::PngEncoder::Options& options) {
            const Encoding e = encode(samples, options, runs);
            std::printf("  %-36s %10zu bytes  %7.3f s wall %7.3f s cpu  %5.1f %% of vips", name.c_str(), e.size, e.time.wall, e.time.cpu,
                        100.0 * double(e.size) / double(vips_size));
            if (options.zlib_for_flat || options.try_unfiltered)
                std::printf("  (%zu pieces: %zu flat, %zu unfiltered, %zu deflated again)", e.statistics.pieces, e.statistics.flat,
                            e.statistics.unfiltered, e.statistics.deflated_again);
            std::printf("\n");
        };
        const ddt::PngEncoder::Options defaults;
        for (int level = 0; level <= 3; ++level)
            for (ddt::PngFilter filter : {ddt::PngFilter::None, ddt::PngFilter::Sub, ddt::PngFilter::Up, ddt::PngFilter::Average,
                                          ddt::PngFilter::Paeth, ddt::PngFilter::Adaptive, ddt::PngFilter::PieceAdaptive}) {
                ddt::PngEncoder::Options options = defaults;
                options.filter = filter;
                options.isal_level = level;
                options.zlib_for_flat = false;
                options.try_unfiltered = false;
                row(std::string("ISA-L only, ") + filterName(filter) + ", level " + std::to_string(level), options);
            }
        for (ddt::PngFilter filter : {ddt::PngFilter::Adaptive, ddt::PngFilter::PieceAdaptive}) {
            ddt::PngEncoder::Options options = defaults;
            options.filter = filter;
            row(std::string("default, ") + filterName(filter), options);
        }
        for (size_t kib : {64, 128, 256, 512, 1024}) {
            ddt::PngEncoder::Options options = defaults;
            options.chunk_bytes = kib * 1024;
            row(std::string("default, ") + std::to_string(kib) + " KiB pieces", options);
        }

        // Whole writes to a file: ddtup's ImageWriter (conversion from float included), and
        // OpenImageIO's PNG writer as ddtup called it before.
        const Timing ours = bestTime(runs, [&] { ddt::writeImage(temp, image); });
        std::printf("  %-36s %10ju bytes  %7.3f s wall %7.3f s cpu\n", "ImageWriter (float rows to file)",
                    uintmax_t(std::filesystem::file_size(temp)), ours.wall, ours.cpu);
        const Timing theirs = bestTime(1, [&] {
            auto output = OIIO::ImageOutput::create(temp);
            const OIIO::TypeDesc type = samples.format.bit_depth == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
            OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels), type);
            spec.attribute("oiio:ColorSpace", "sRGB");
            spec.attribute("oiio:UnassociatedAlpha", 1);
            if (!output->open(temp, spec) || !output->write_image(type, samples.native.data()) || !output->close())
                std::fprintf(stderr, "OpenImageIO: %s\n", output->geterror().c_str());
        });
        std::printf("  %-36s %10ju bytes  %7.3f s wall %7.3f s cpu (one run)\n", "OpenImageIO 2.4's PNG writer",
                    uintmax_t(std::filesystem::file_size(temp)), theirs.wall, theirs.cpu);
        std::filesystem::remove(temp);
    }
    return 0;
}
