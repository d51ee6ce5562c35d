// The ten formats ddtup accepts, each with its seeds and the damage that knows its layout.
#pragma once

#include <string>
#include <vector>

#include "damage.h"
#include "random.h"
#include "seeds.h"

namespace fuzz {

struct Format {
    std::string name;       // "png": the report's rows and the damaged files' names
    size_t signature_size;  // bytes RandomBody keeps
    // Damage of the kinds Size, PixelFormat, Structure and Stream, done knowing the layout
    // and leaving checksums valid; returns what it did.
    std::string (*damage)(std::string& file, DamageKind kind, Random& random);
    // Recomputes the checksums the decoder checks, where it will look for them; null when
    // the format has none.
    void (*repair)(std::string& file);
};

const std::vector<Format>& allFormats();
const Format* findFormat(const std::string& name);

// The structured damage of each format, one file each.
std::string damagePng(std::string& file, DamageKind kind, Random& random);
void repairPngCrcs(std::string& file);
std::string damageJpeg(std::string& file, DamageKind kind, Random& random);
std::string damageTiff(std::string& file, DamageKind kind, Random& random);
std::string damageExr(std::string& file, DamageKind kind, Random& random);
std::string damageWebp(std::string& file, DamageKind kind, Random& random);
std::string damageBmp(std::string& file, DamageKind kind, Random& random);
std::string damageGif(std::string& file, DamageKind kind, Random& random);
std::string damageTarga(std::string& file, DamageKind kind, Random& random);
std::string damagePnm(std::string& file, DamageKind kind, Random& random);
std::string damageHdr(std::string& file, DamageKind kind, Random& random);

}  // namespace fuzz
