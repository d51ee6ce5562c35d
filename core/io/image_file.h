// Image files: reading (image_reader.cpp) and writing (image_writer.cpp); PNG and JPEG by
// ddtup's own code over libspng, libjpeg-turbo and its parallel PNG encoder, the other formats
// by OpenImageIO's codecs in a module loaded when needed (codec_module.h). Kept apart from
// core/image.h so that code without file I/O links none of it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "image.h"
#include "packed_image.h"

namespace ddt {

// Opens an image file and reads its header; the pixels follow with read(). Splitting the two
// lets a caller check sizes and open the output before the expensive decode.
// Any format of image_formats.h, recognised by content; "-" reads standard input (copied to a
// temporary file first: codecs seek). Throws UserError("PATH: reason") for a missing, empty or
// non-image file, a folder, a channel layout other than the four above, or more than
// kMaxInputPixels pixels. The image is made upright by its EXIF orientation; of a file with
// several images (pages, frames) the first is used, with a note.
class ImageReader {
public:
    explicit ImageReader(const std::string& path);
    ~ImageReader();
    ImageReader(const ImageReader&) = delete;
    ImageReader& operator=(const ImageReader&) = delete;

    // The upright size, layout, sample type and metadata; `pixels` is empty.
    const Image& header() const { return header_; }
    // Decodes the pixels (premultiplied when there is alpha). Throws UserError for a truncated
    // or corrupt file, or NaN or infinite samples. Call one of the two, once.
    Image read();
    // The same pixels, kept in the file's sample type where it is 8 or 16 bits (packed_image.h).
    // With `rows_as_needed`, a JPEG or a PNG that is not interlaced, stored upright, is read
    // through here (a damaged file fails here, as without), then decoded again as
    // PackedImage::holdRows asks, its rows freed as the tiles pass (the file stays open until
    // then); any other file is decoded whole here, as without.
    PackedImage readPacked(bool rows_as_needed = false);
    // Bytes per sample readPacked keeps: 1 or 2 for codes, 4 for floats.
    uint32_t keptSampleBytes() const;
    // One-line remarks for the user ("PATH: has more than one image (pages or frames); using the first").
    const std::vector<std::string>& notes() const { return notes_; }

private:
    // Every sample of the image as `Sample`s, upright.
    template <class Sample>
    std::vector<Sample> decode();

    struct State;
    std::unique_ptr<State> state_;
    Image header_;
    std::vector<std::string> notes_;
};

// Reads a whole image through ImageReader.
Image readImage(const std::string& path);

// How an image is written; the defaults follow the input.
struct WriteOptions {
    int quality = 95;                 // 1..100, for the lossy formats (JPEG, WebP)
    std::optional<SampleType> depth;  // the sample type to write; default: the input's
    std::string format;               // a file extension ("png") that overrides the path's;
                                      // required when writing standard output
};

// "" if the format named by `format` (an extension), else by `path`'s extension, can hold a
// width × height image, else the reason. Some codecs fail only after all the work, or end
// the process (libjpeg), so the known limits are checked before anything is opened.
std::string checkOutputFormat(const std::string& path, uint32_t width, uint32_t height,
                              const std::string& format = "");

// Writes an image in bands of rows, to a temporary file in the output's folder that is
// renamed over the output only by commit(): a failed, interrupted or abandoned write leaves
// nothing. "-" writes standard output (through a temporary file in $TMPDIR, as codecs seek).
// The sample type follows options.depth, else `like`, where the format can hold it, else the
// nearest it supports (reported in notes()). `like` may be a header without pixels; its size
// scales the resolution (dots per inch) metadata. Every write is checked: a full disk is a
// UserError("PATH: No space left on device").
class ImageWriter {
public:
    ImageWriter(const std::string& path, uint32_t width, uint32_t height, const Image& like,
                const WriteOptions& options = {});
    ~ImageWriter();
    ImageWriter(const ImageWriter&) = delete;
    ImageWriter& operator=(const ImageWriter&) = delete;

    // Rows [y_begin, y_end) in order, `like.channels` floats per pixel, premultiplied like Image.
    void writeRows(uint32_t y_begin, uint32_t y_end, const float* rows);
    void commit();
    const std::vector<std::string>& notes() const { return notes_; }
    // 8 or 16 where writeRows makes its floats 8- or 16-bit codes by quantiseRow
    // (core/io/sample_quantise.h) and nothing else (ddtup's own PNG and JPEG writers, the
    // channels as given): a caller may then give those codes to writeCodes instead, for the
    // same file. 0 for every other writer.
    uint32_t codeBits() const;
    // Rows [y_begin, y_end) as such codes, where codeBits() is 8 or 16 respectively.
    void writeCodes(uint32_t y_begin, uint32_t y_end, const uint8_t* codes);
    void writeCodes(uint32_t y_begin, uint32_t y_end, const uint16_t* codes);

private:
    struct State;
    std::unique_ptr<State> state_;
    std::vector<std::string> notes_;
};

// Writes a whole image through ImageWriter; returns its notes.
std::vector<std::string> writeImage(const std::string& path, const Image& image, const WriteOptions& options = {});

}  // namespace ddt
