// The kinds of damage done to a valid file, and the generic ones that need no knowledge of
// the format beyond its signature and checksums. The report counts format × kind.
#pragma once

#include <string>

#include "random.h"

namespace fuzz {

enum class DamageKind {
    Truncate,     // cut short: in the header, in the data, or by a few bytes
    BitFlip,      // a few bits flipped past the signature, checksums recomputed
    RandomBody,   // a valid signature followed by random bytes
    Size,         // the width and height fields
    PixelFormat,  // depth, channels, colour type, compression, sample format
    Structure,    // chunk / marker / entry lengths, offsets, counts, tables, palettes
    Stream,       // the compressed or coded pixel data, its own checksums recomputed
};
constexpr DamageKind kDamageKinds[] = {DamageKind::Truncate, DamageKind::BitFlip,     DamageKind::RandomBody,
                                       DamageKind::Size,     DamageKind::PixelFormat, DamageKind::Structure,
                                       DamageKind::Stream};

const char* damageKindName(DamageKind kind);  // "truncate", "bit-flip", …

struct Format;

// Damages a valid `file` of `format` in place; returns what was done, in words, for the
// failure record.
std::string damageFile(const Format& format, DamageKind kind, std::string& file, Random& random);

}  // namespace fuzz
