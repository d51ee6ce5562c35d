#include "oiio_output.h"

#include <OpenImageIO/imageio.h>
#include <sys/statvfs.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "checked_file.h"
#include "image_metadata.h"
#include "oiio_codec.h"
#include "oiio_metadata.h"
#include "user_error.h"

namespace ddt {

namespace {

void closeQuietly(OIIO::ImageOutput& output) {
    QuietStderr quiet;  // libpng complains about a file closed without pixels
    output.close();
}

// Whether the file system holding `path` has no space left, to name the cause of a failed
// write by a codec that writes its file itself (TIFF) and reports it in its own words.
bool noSpaceLeft(const std::string& path) {
    struct statvfs status {};
    return ::statvfs(path.c_str(), &status) == 0 && status.f_bavail == 0;
}

class OiioOutput final : public CodecOutput {
public:
    OiioOutput(const OutputRequest& request, OutputLayout& layout)
        : path_(request.temp_path), name_(request.name), output_(OIIO::ImageOutput::create(request.format->oiio_name)) {
        if (!output_) throw std::runtime_error(std::string("OpenImageIO has no ") + request.format->title + " writer");
        // OIIO 2.4's TIFF writer loses the main directory when it writes EXIF data through a
        // proxy (measured, with OIIO's own IOFile too); libtiff reports failed writes itself.
        checked_ = output_->supports("ioproxy") && output_->format_name() != std::string("tiff");
        auto openAs = [&](OIIO::TypeDesc type) {
            OIIO::ImageSpec spec(int(request.width), int(request.height), int(layout.out_channels), type);
            addAttributes(request.attributes, spec);
            spec.channelnames = channelNames(layout.out_channels);
            spec.alpha_channel = layout.out_alpha ? int(layout.out_channels) - 1 : -1;
            if (checked_) {
                // Each attempt starts an empty file: a refused one may have written a header.
                openCheckedFile();
                proxy_ = std::make_unique<CheckedFileProxy>(*file_);
                output_->set_ioproxy(proxy_.get());
            }
            QuietStderr quiet;
            return output_->open(path_, spec);
        };

        const OIIO::TypeDesc wanted = typeDescOf(request.wanted);
        if (!openAs(wanted)) {
            // Some formats hold no grey (WebP, GIF, HDR) or no grey+alpha (BMP): try RGB(A).
            if (layout.out_channels > 2 || layout.grey_to_rgb) throw failure();
            UserError first_failure = failure();
            expandGreyToRgb(layout);
            if (!openAs(wanted)) {
                codecError(*output_);  // drop the second attempt's message, the first says more
                throw first_failure;
            }
        }
        // Formats that cannot hold a type fall back to 8 bits in OIIO 2.4 (PNG turns float into
        // 8-bit), while 16 bits is nearer for anything wider: ask for it once.
        if (sampleTypeOf(output_->spec().format) == SampleType::UInt8 && request.wanted != SampleType::UInt8) {
            closeQuietly(*output_);
            if (!openAs(OIIO::TypeDesc::UINT16)) {
                codecError(*output_);  // this format refuses 16 bits: back to its own choice
                if (!openAs(wanted)) throw failure();
            }
        }
    }

    ~OiioOutput() override {
        if (output_) closeQuietly(*output_);
    }

    SampleType written() const override { return sampleTypeOf(output_->spec().format); }

    void writeRows(uint32_t y_begin, uint32_t y_end, const float* rows) override {
        bool ok;
        {
            QuietStderr quiet;
            ok = output_->write_scanlines(int(y_begin), int(y_end), 0, OIIO::TypeDesc::FLOAT, rows);
        }
        if (!ok || (file_ && file_->failure())) throw failure();
    }

    void finish() override {
        bool ok;
        {
            QuietStderr quiet;
            ok = output_->close();
        }
        if (file_) file_->close();
        if (!ok || (file_ && file_->failure())) throw failure();
        output_.reset();
    }

private:
    // The reason a write failed: the file's own error where it saw one, since codecs that
    // ignore failed writes report something vaguer or nothing.
    UserError failure() {
        const std::string codec_reason = firstLine(codecError(*output_));  // read either way: it clears it
        if (file_ && file_->failure()) return UserError(name_ + ": " + std::strerror(file_->failure()));
        if (!file_ && noSpaceLeft(path_)) return UserError(name_ + ": " + std::strerror(ENOSPC));
        return UserError(name_ + ": cannot write (" + codec_reason + ")");
    }

    // Opens the output file as a CheckedFile, empty.
    void openCheckedFile() {
        proxy_.reset();
        file_.reset();
        try {
            file_ = std::make_unique<CheckedFile>(path_);
        } catch (const std::system_error& error) {
            throw UserError(name_ + ": cannot write (" + std::strerror(error.code().value()) + ")");
        }
    }

    std::string path_;
    std::string name_;
    bool checked_ = false;
    std::unique_ptr<CheckedFile> file_;           // null for the few codecs that cannot write through one
    std::unique_ptr<CheckedFileProxy> proxy_;     // `file_` as OIIO's writer sees it
    std::unique_ptr<OIIO::ImageOutput> output_;  // declared last: closed before the file goes
};

}  // namespace

std::unique_ptr<CodecOutput> openOiioOutput(const OutputRequest& request, OutputLayout& layout) {
    return std::make_unique<OiioOutput>(request, layout);
}

bool oiioWritesAlpha(const ImageFormat& format) {
    const std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(format.oiio_name);
    return output && output->supports("alpha");
}

}  // namespace ddt
