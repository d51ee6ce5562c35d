#include "xmp.h"

#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

#include "xmp_tags.h"

namespace ddt {

namespace {

using Base = AttributeType::Base;

const XmpTag* tagNamed(std::string_view name) {
    for (const XmpTag& tag : xmpTags())
        if (sameName(tag.name, name)) return &tag;
    return nullptr;
}

// The property's value: a single string as it is (up to a NUL, as OpenImageIO reads it), a
// single int by %d (or True / False), a single float by %g; "" for any other type, which
// OpenImageIO leaves out.
std::string propertyValue(const ImageAttribute& attribute, const XmpTag& tag) {
    const AttributeType& type = attribute.type;
    if (!type.isScalar() || type.meaning != AttributeType::Meaning::None) return "";
    if (type.base == Base::String) return attribute.strings.empty() ? "" : attribute.strings[0].c_str();
    char text[32] = "";
    if (type.base == Base::Int32) {
        int32_t value;
        std::memcpy(&value, attribute.bytes.data(), sizeof value);
        if (tag.flags & XmpTag::kTrueFalse) return value ? "True" : "False";
        std::snprintf(text, sizeof text, "%d", value);
    } else if (type.base == Base::Float) {
        float value;
        std::memcpy(&value, attribute.bytes.data(), sizeof value);
        std::snprintf(text, sizeof text, "%g", double(value));
    }
    return text;
}

struct Property {
    const XmpTag* tag;
    std::string value;
};

bool inNamespace(const XmpTag& tag, const XmpNamespace& space) {
    const size_t length = std::strlen(space.prefix);
    return sameName(std::string_view(tag.name).substr(0, length), space.prefix) && tag.name[length] == ':';
}

}  // namespace

std::string encodeXmp(const ImageAttributes& attributes) {
    // The properties in the attributes' order; a repeated attribute gives its property again.
    std::vector<Property> properties;
    for (const ImageAttribute& attribute : attributes.all())
        if (const XmpTag* tag = tagNamed(attribute.name)) {
            std::string value = propertyValue(attribute, *tag);
            if (!value.empty()) properties.push_back({tag, std::move(value)});
        }

    // One rdf:Description a namespace, its properties as XML attributes. Values are not
    // escaped: OpenImageIO writes them as they are.
    std::string descriptions;
    for (const XmpNamespace& space : xmpNamespaces()) {
        std::string list;
        for (const Property& property : properties)
            if (inNamespace(*property.tag, space)) {
                if (!list.empty()) list += ' ';
                list.append(property.tag->name).append("=\"").append(property.value).append("\"");
            }
        if (!list.empty())
            descriptions += std::string("<rdf:Description rdf:about=\"\" xmlns:") + space.prefix + "=\"" + space.uri +
                            "\" " + list + "/> ";
    }
    if (descriptions.empty()) return "";
    return "<?xpacket begin=\"\xEF\xBB\xBF\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?> "
           "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\" x:xmptk=\"Adobe XMP Core 5.5-c002 1.148022, "
           "2012/07/15-18:06:45        \"> <rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"> " +
           descriptions + " </rdf:RDF> </x:xmpmeta> <?xpacket end=\"w\"?>";
}

}  // namespace ddt
