// The XMP properties OpenImageIO 2.4's encode_xmp writes, and the XMP namespaces it writes them in.
#pragma once

#include <cstdint>
#include <span>

namespace ddt {

struct XmpTag {
    enum Flag : uint8_t {
        kTrueFalse = 1,  // an int written as True / False
    };
    const char* name;  // the XMP property's name, which is also the attribute's
    uint8_t flags;
};

// A namespace: its prefix (the start of its properties' names, up to ':') and URI.
struct XmpNamespace {
    const char* prefix;
    const char* uri;
};

// The properties OpenImageIO writes. Its table has many more (photoshop:City from "IPTC:City",
// dc:Description from "ImageDescription", …), but it finds an attribute's entry by the XMP name
// and then wants the attribute's name to be the entry's attribute name as well, so only the
// entries whose two names are one can be found. Of those, tiff:Compression,
// tiff:PlanarConfiguration, tiff:PhotometricInterpretation and tiff:subfiletype are
// redundant with TIFF tags and a JPEG's packet is "minimal", which writes redundant ones only
// beside other tiff: properties, of which there are none; exif:ColorSpace and aux:Firmware
// belong to no namespace it writes. So none of those six ever reaches a packet.
std::span<const XmpTag> xmpTags();

// The namespaces in the packet's order.
std::span<const XmpNamespace> xmpNamespaces();

}  // namespace ddt
