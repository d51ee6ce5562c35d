#include "formats.h"

namespace fuzz {

const std::vector<Format>& allFormats() {
    // Signature sizes: PNG's 8 bytes; JPEG's SOI and the first marker; TIFF's byte order and
    // 42; EXR's magic; "RIFF" size "WEBP"; "BM"; "GIF89a"; Targa has none (its extension
    // names it), PNM's magic and HDR's "#?RADIANCE" line.
    static const std::vector<Format> formats = {
        {"png", 8, damagePng, repairPngCrcs},
        {"jpeg", 3, damageJpeg, nullptr},
        {"tiff", 4, damageTiff, nullptr},
        {"openexr", 4, damageExr, nullptr},
        {"webp", 12, damageWebp, nullptr},
        {"bmp", 2, damageBmp, nullptr},
        {"gif", 6, damageGif, nullptr},
        {"targa", 0, damageTarga, nullptr},
        {"pnm", 3, damagePnm, nullptr},
        {"hdr", 11, damageHdr, nullptr},
    };
    return formats;
}

const Format* findFormat(const std::string& name) {
    for (const Format& format : allFormats())
        if (format.name == name) return &format;
    return nullptr;
}

}  // namespace fuzz
