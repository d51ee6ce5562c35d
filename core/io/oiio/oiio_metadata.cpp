#include "oiio_metadata.h"

#include <algorithm>
#include <optional>

namespace ddt {

namespace {

using Base = AttributeType::Base;
using Meaning = AttributeType::Meaning;

// Each of ddtup's base types and meanings, and OpenImageIO's.
const std::pair<Base, OIIO::TypeDesc::BASETYPE> kBases[] = {
    {Base::UInt8, OIIO::TypeDesc::UINT8},   {Base::Int8, OIIO::TypeDesc::INT8},     {Base::UInt16, OIIO::TypeDesc::UINT16},
    {Base::Int16, OIIO::TypeDesc::INT16},   {Base::UInt32, OIIO::TypeDesc::UINT32}, {Base::Int32, OIIO::TypeDesc::INT32},
    {Base::UInt64, OIIO::TypeDesc::UINT64}, {Base::Int64, OIIO::TypeDesc::INT64},   {Base::Half, OIIO::TypeDesc::HALF},
    {Base::Float, OIIO::TypeDesc::FLOAT},   {Base::Double, OIIO::TypeDesc::DOUBLE}, {Base::String, OIIO::TypeDesc::STRING},
};
const std::pair<Meaning, OIIO::TypeDesc::VECSEMANTICS> kMeanings[] = {
    {Meaning::None, OIIO::TypeDesc::NOSEMANTICS}, {Meaning::Colour, OIIO::TypeDesc::COLOR},
    {Meaning::Point, OIIO::TypeDesc::POINT},      {Meaning::Vector, OIIO::TypeDesc::VECTOR},
    {Meaning::Normal, OIIO::TypeDesc::NORMAL},    {Meaning::Timecode, OIIO::TypeDesc::TIMECODE},
    {Meaning::Keycode, OIIO::TypeDesc::KEYCODE},  {Meaning::Rational, OIIO::TypeDesc::RATIONAL},
    {Meaning::Box, OIIO::TypeDesc::BOX},
};

std::optional<AttributeType> attributeTypeOf(OIIO::TypeDesc type) {
    AttributeType ours;
    bool known = false;
    for (const auto& [base, theirs] : kBases)
        if (type.basetype == theirs) {
            ours.base = base;
            known = true;
        }
    if (!known || type.arraylen < 0) return std::nullopt;
    for (const auto& [meaning, theirs] : kMeanings)
        if (type.vecsemantics == theirs) ours.meaning = meaning;
    ours.aggregate = type.aggregate;
    ours.array_length = uint32_t(type.arraylen);
    return ours;
}

OIIO::TypeDesc typeDescOf(const AttributeType& ours) {
    OIIO::TypeDesc::BASETYPE base = OIIO::TypeDesc::UNKNOWN;
    for (const auto& [mine, theirs] : kBases)
        if (ours.base == mine) base = theirs;
    OIIO::TypeDesc::VECSEMANTICS meaning = OIIO::TypeDesc::NOSEMANTICS;
    for (const auto& [mine, theirs] : kMeanings)
        if (ours.meaning == mine) meaning = theirs;
    return OIIO::TypeDesc(base, OIIO::TypeDesc::AGGREGATE(ours.aggregate), meaning, int(ours.array_length));
}

}  // namespace

ImageAttributes attributesOf(const OIIO::ImageSpec& spec) {
    ImageAttributes attributes;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        std::optional<AttributeType> type = attributeTypeOf(p.type());
        if (!type) continue;
        // Several values of a type (a ParamValue's nvalues) are kept as an array of them.
        if (p.nvalues() > 1) type->array_length = uint32_t(p.nvalues()) * std::max(type->array_length, 1u);
        ImageAttribute attribute{p.name().string(), *type, {}, {}};
        const size_t count = type->valueCount();
        if (type->base == Base::String) {
            const auto* strings = static_cast<const OIIO::ustring*>(p.data());
            for (size_t i = 0; i < count; ++i) attribute.strings.push_back(strings[i].string());
        } else {
            const auto* bytes = static_cast<const uint8_t*>(p.data());
            attribute.bytes.assign(bytes, bytes + count * type->valueBytes());
        }
        attributes.append(std::move(attribute));
    }
    return attributes;
}

void addAttributes(const ImageAttributes& attributes, OIIO::ImageSpec& spec) {
    for (const ImageAttribute& attribute : attributes.all()) {
        const OIIO::TypeDesc type = typeDescOf(attribute.type);
        if (attribute.type.base == Base::String) {
            std::vector<OIIO::ustring> strings(attribute.strings.begin(), attribute.strings.end());
            spec.extra_attribs.emplace_back(attribute.name, type, 1, strings.data());
        } else {
            spec.extra_attribs.emplace_back(attribute.name, type, 1, attribute.bytes.data());
        }
    }
}

}  // namespace ddt
