// The image formats ddtup reads and writes.
//
// Debian's OpenImageIO has 28 readers (video, DICOM, camera RAW, PSD, DDS, HEIF…) and, asked to
// open a file, tries each of them in turn until one accepts it. Every reader is a decoder fed
// with untrusted bytes, so ddtup hands files only to the readers of a fixed list, which are the
// ones scripts/fuzz damages files for, and refuses the rest with one line. The folder walk
// (-i) and the output format (-f, the output's extension) follow the same list.
#pragma once

#include <string>
#include <vector>

namespace ddt {

struct ImageFormat {
    const char* oiio_name;   // OpenImageIO's name of the format: the reader and writer to create
    const char* title;       // the name a person knows it by, for messages
    const char* extensions;  // its file extensions, lower case, each after a space: OpenImageIO 2.4's list
};

// The formats, in the order messages list them.
const std::vector<ImageFormat>& imageFormats();

// "PNG, JPEG, TIFF, …", for messages.
std::string imageFormatTitles();

// The format whose file extension (with or without the dot, any case) is `extension`; null
// when it is none of ours.
const ImageFormat* formatOfExtension(const std::string& extension);

// The format of the file at `path` by its first bytes; Targa, which has no signature, by the
// extension of `name` (the name the user gave, for a copy of standard input: none). Null when
// it is none of ours or the file cannot be read.
const ImageFormat* formatOfContent(const std::string& path, const std::string& name);

}  // namespace ddt
