// Point files in PLY (core/io/point_file.h): the vertex element's x, y and colours.
// The format: Greg Turk's "The PLY Polygon File Format" (1994), as Paul Bourke's page
// (paulbourke.net/dataformats/ply) keeps it. ddtup's own writer is core/io/ply_format.cpp.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>

#include "point_file.h"

namespace ddt {

namespace {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

// The scalar types, by both the 1994 names and the sized ones later writers use.
struct ScalarType {
    const char* name;
    const char* sized_name;
    uint32_t bytes;
    bool integer;
    double lowest, highest;  // of the integer types, for ascii values
};
constexpr ScalarType kScalarTypes[] = {
    {"char", "int8", 1, true, -128.0, 127.0},
    {"uchar", "uint8", 1, true, 0.0, 255.0},
    {"short", "int16", 2, true, -32768.0, 32767.0},
    {"ushort", "uint16", 2, true, 0.0, 65535.0},
    {"int", "int32", 4, true, -2147483648.0, 2147483647.0},
    {"uint", "uint32", 4, true, 0.0, 4294967295.0},
    {"float", "float32", 4, false, 0.0, 0.0},
    {"double", "float64", 8, false, 0.0, 0.0},
};
using Scalar = const ScalarType*;

Scalar scalarNamed(std::string_view name) {
    for (const ScalarType& type : kScalarTypes)
        if (name == type.name || name == type.sized_name) return &type;
    return nullptr;
}

struct PlyProperty {
    std::string name;
    Scalar type = nullptr;        // of the value, or of a list's items
    Scalar count_type = nullptr;  // a list's length; null for a scalar property
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    size_t data_start = 0;  // the offset of the first byte after end_header's line
};

std::vector<std::string_view> wordsOf(std::string_view line) {
    std::vector<std::string_view> words;
    size_t at = 0;
    while ((at = line.find_first_not_of(" \t\r", at)) != std::string_view::npos) {
        const size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
        words.push_back(line.substr(at, end - at));
        at = end;
    }
    return words;
}

PlyHeader parseHeader(const std::string& name, std::string_view bytes) {
    PlyHeader header;
    bool has_format = false;
    size_t at = 0;
    for (uint64_t line_number = 1;; ++line_number) {
        if (at >= bytes.size()) throw UserError(name + ": bad PLY header: it has no end_header line");
        const size_t end = std::min(bytes.find('\n', at), bytes.size());
        const std::vector<std::string_view> words = wordsOf(bytes.substr(at, end - at));
        at = end + 1;
        auto bad = [&](const std::string& reason) {
            return UserError(name + ": bad PLY header: line " + std::to_string(line_number) + ": " + reason);
        };
        if (line_number == 1) {
            if (words.size() != 1 || words[0] != "ply") throw UserError(name + ": not a PLY file (it does not start with \"ply\")");
            continue;
        }
        if (words.empty()) continue;
        const std::string_view keyword = words[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") break;
        if (keyword == "format") {
            if (has_format) throw bad("a second format line");
            if (words.size() != 3 || words[2] != "1.0") throw bad("expected `format ascii|binary_little_endian|binary_big_endian 1.0`");
            if (words[1] == "ascii") header.format = PlyFormat::Ascii;
            else if (words[1] == "binary_little_endian") header.format = PlyFormat::BinaryLittleEndian;
            else if (words[1] == "binary_big_endian") header.format = PlyFormat::BinaryBigEndian;
            else throw bad("unknown format \"" + std::string(words[1]) + "\"");
            has_format = true;
        } else if (keyword == "element") {
            PlyElement element;
            if (words.size() != 3) throw bad("expected `element NAME COUNT`");
            const auto [end_count, error] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
            if (error != std::errc() || end_count != words[2].data() + words[2].size())
                throw bad("the element count \"" + std::string(words[2]) + "\" is not a whole number");
            element.name = words[1];
            header.elements.push_back(element);
        } else if (keyword == "property") {
            if (header.elements.empty()) throw bad("a property before any element");
            PlyProperty property;
            const bool list = words.size() > 1 && words[1] == "list";
            if (words.size() != (list ? 5u : 3u))
                throw bad(list ? "expected `property list COUNT_TYPE ITEM_TYPE NAME`" : "expected `property TYPE NAME`");
            for (size_t k = list ? 2 : 1; k + 1 < words.size(); ++k)
                if (!scalarNamed(words[k])) throw bad("unknown property type \"" + std::string(words[k]) + "\"");
            property.type = scalarNamed(words[words.size() - 2]);
            if (list) property.count_type = scalarNamed(words[2]);
            if (list && !property.count_type->integer) throw bad("a list's length must have an integer type");
            property.name = words.back();
            header.elements.back().properties.push_back(property);
        } else {
            throw bad("unknown keyword \"" + std::string(keyword.substr(0, 24)) + "\"");
        }
    }
    if (!has_format) throw UserError(name + ": bad PLY header: it has no format line");
    header.data_start = std::min(at, bytes.size());
    return header;
}

// The data after the header, read in order: values of the binary formats at an offset,
// whitespace-separated numbers of the ascii one.
class PlyData {
public:
    PlyData(const std::string& name, PlyFormat format, std::string_view bytes, size_t start)
        : name_(name), format_(format), bytes_(bytes), at_(start) {}

    bool ascii() const { return format_ == PlyFormat::Ascii; }
    size_t remaining() const { return bytes_.size() - at_; }

    // The next value, of `type`. Throws UserError when the data ends (naming item `index` of
    // `element`) or, in ascii, when the word is not a number of `type`.
    double next(Scalar type, const PlyElement& element, uint64_t index, const PlyProperty& property) {
        if (ascii()) return nextWord(type, element, index, property);
        if (remaining() < type->bytes) throw truncated(element, index);
        const char* at = bytes_.data() + at_;
        at_ += type->bytes;
        switch (type - kScalarTypes) {
        case 0: return load<int8_t>(at);
        case 1: return load<uint8_t>(at);
        case 2: return load<int16_t>(at);
        case 3: return load<uint16_t>(at);
        case 4: return load<int32_t>(at);
        case 5: return load<uint32_t>(at);
        case 6: return load<float>(at);
        default: return load<double>(at);
        }
    }

    // Skips `count` values of `type`.
    void skip(uint64_t count, Scalar type, const PlyElement& element, uint64_t index, const PlyProperty& property) {
        if (!ascii()) {
            if (count > remaining() / type->bytes) throw truncated(element, index);
            at_ += count * type->bytes;
            return;
        }
        for (uint64_t k = 0; k < count; ++k) nextWord(type, element, index, property);
    }

    UserError truncated(const PlyElement& element, uint64_t index) const {
        return UserError(name_ + ": truncated: the data ends within " + element.name + " " + std::to_string(index) +
                         " of the " + std::to_string(element.count) + " the header declares (counting from 0)");
    }
    UserError failure(const PlyElement& element, uint64_t index, const std::string& reason) const {
        return UserError(name_ + ": " + element.name + " " + std::to_string(index) + " (counting from 0): " + reason);
    }

private:
    template <typename T>
    T load(const char* at) const {
        char bytes[sizeof(T)];
        std::memcpy(bytes, at, sizeof(T));
        if ((format_ == PlyFormat::BinaryBigEndian) != (std::endian::native == std::endian::big))
            std::reverse(bytes, bytes + sizeof(T));
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }

    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

    // The next word as a number of `type` (NaN and infinity pass as floats, for the caller to
    // refuse by name).
    double nextWord(Scalar type, const PlyElement& element, uint64_t index, const PlyProperty& property) {
        while (at_ < bytes_.size() && isSpace(bytes_[at_])) ++at_;
        if (at_ == bytes_.size()) throw truncated(element, index);
        const char* begin = bytes_.data() + at_;
        while (at_ < bytes_.size() && !isSpace(bytes_[at_])) ++at_;
        const char* end = bytes_.data() + at_;
        double value = 0;
        const auto [parsed_end, error] = std::from_chars(begin, end, value);
        const bool in_type =
            !type->integer || (value >= type->lowest && value <= type->highest && std::floor(value) == value);
        if (error != std::errc() || parsed_end != end || !in_type) {
            std::string word(begin, std::min<size_t>(size_t(end - begin), 24));
            for (char& c : word)
                if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
            throw failure(element, index, "property " + property.name + ": \"" + word + "\" is not a " + type->name);
        }
        return value;
    }

    const std::string& name_;
    PlyFormat format_;
    std::string_view bytes_;
    size_t at_;
};

// Reads past every item of an element the points do not come from.
void skipElement(PlyData& data, const PlyElement& element) {
    if (element.properties.empty()) return;
    const bool fixed = std::none_of(element.properties.begin(), element.properties.end(),
                                    [](const PlyProperty& p) { return p.count_type != nullptr; });
    if (fixed && !data.ascii()) {  // all at once: the count may be large
        uint64_t item_bytes = 0;
        for (const PlyProperty& property : element.properties) item_bytes += property.type->bytes;
        if (element.count > data.remaining() / item_bytes)
            throw data.truncated(element, data.remaining() / item_bytes);
        data.skip(element.count * item_bytes, scalarNamed("uchar"), element, 0, element.properties[0]);  // as bytes
        return;
    }
    // Each item takes at least one byte or word, so a false count ends with the data.
    for (uint64_t index = 0; index < element.count; ++index)
        for (const PlyProperty& property : element.properties) {
            uint64_t length = 1;
            if (property.count_type) {
                const double count = data.next(property.count_type, element, index, property);
                if (count < 0) throw data.failure(element, index, "property " + property.name + " has a negative list length");
                length = uint64_t(count);
            }
            data.skip(length, property.type, element, index, property);
        }
}

// What each vertex property becomes.
enum Role : int { kSkip = -3, kX = -2, kY = -1 };  // 0..3: colour channel (red, green, blue, alpha)

std::vector<int> vertexRoles(const std::string& name, const PlyElement& vertex, uint32_t& channels, Scalar& colour_type) {
    static const char* const kNames[] = {"x", "y", "red", "green", "blue", "alpha"};
    std::vector<int> roles;
    int found[6] = {-1, -1, -1, -1, -1, -1};  // property index by kNames
    for (size_t p = 0; p < vertex.properties.size(); ++p) {
        const PlyProperty& property = vertex.properties[p];
        if (property.count_type)
            throw UserError(name + ": the vertex element has a list property (" + property.name + "), which ddtup does not read");
        roles.push_back(kSkip);
        for (int k = 0; k < 6; ++k)
            if (property.name == kNames[k]) {
                if (found[k] >= 0) throw UserError(name + ": the vertex property " + property.name + " appears twice");
                found[k] = int(p);
                roles.back() = k - 2;
            }
    }
    if (found[0] < 0 || found[1] < 0) throw UserError(name + ": no vertex positions (properties x and y)");
    for (int k = 0; k < 2; ++k) {
        const Scalar type = vertex.properties[found[k]].type;
        if (type->integer)
            throw UserError(name + ": the vertex property " + kNames[k] + " is " + type->name + " (x and y must be float or double)");
    }
    if (found[2] < 0 || found[3] < 0 || found[4] < 0)
        throw UserError(name + ": no vertex colours (properties red, green and blue)");
    channels = found[5] >= 0 ? 4 : 3;
    colour_type = vertex.properties[found[2]].type;
    for (uint32_t k = 0; k < channels; ++k) {
        const Scalar type = vertex.properties[found[2 + k]].type;
        if (type != colour_type)
            throw UserError(name + ": the colour properties have different types (" + colour_type->name + " and " + type->name + ")");
    }
    if (colour_type->integer && colour_type->highest != 255.0 && colour_type->highest != 65535.0)
        throw UserError(name + ": the colour properties are " + colour_type->name + " (ddtup reads uchar, ushort, float or double)");
    return roles;
}

}  // namespace

PointSamples parsePlyPoints(const std::string& name, std::string_view bytes) {
    const PlyHeader header = parseHeader(name, bytes);
    const auto vertex = std::find_if(header.elements.begin(), header.elements.end(),
                                     [](const PlyElement& element) { return element.name == "vertex"; });
    if (vertex == header.elements.end()) throw UserError(name + ": no vertex element");
    PointSamples points;
    Scalar colour_type = nullptr;
    const std::vector<int> roles = vertexRoles(name, *vertex, points.channels, colour_type);
    if (vertex->count == 0) throw UserError(name + ": no points (the vertex element is empty)");
    if (vertex->count > kMaxPoints)
        throw UserError(name + ": " + std::to_string(vertex->count) + " points, more than " + std::to_string(kMaxPoints) +
                        " (the most ddtup reads)");

    PlyData data(name, header.format, bytes, header.data_start);
    for (auto element = header.elements.begin(); element != vertex; ++element) skipElement(data, *element);

    // A false count must not allocate: a vertex takes at least a byte (a word) per property.
    const uint64_t reserved = std::min<uint64_t>(vertex->count, data.remaining() / roles.size() + 1);
    points.x.reserve(reserved), points.y.reserve(reserved), points.values.reserve(reserved * points.channels);
    const double scale = colour_type->integer ? colour_type->highest : 1.0;
    points.sample_type = scale == 255.0 ? SampleType::UInt8 : scale == 65535.0 ? SampleType::UInt16 : SampleType::Float;
    for (uint64_t index = 0; index < vertex->count; ++index) {
        double x = 0, y = 0, colour[4] = {};
        for (size_t p = 0; p < roles.size(); ++p) {
            const PlyProperty& property = vertex->properties[p];
            if (roles[p] == kSkip) {
                data.skip(1, property.type, *vertex, index, property);
                continue;
            }
            const double value = data.next(property.type, *vertex, index, property);
            if (roles[p] == kX) x = value;
            else if (roles[p] == kY) y = value;
            else colour[roles[p]] = value;
        }
        std::string problem = coordinateProblem(x, y);
        for (uint32_t k = 0; k < points.channels && problem.empty(); ++k) problem = colourProblem(colour[k], scale);
        if (!problem.empty()) throw data.failure(*vertex, index, problem);
        points.x.push_back(x + 0.0);  // + 0.0: -0 becomes 0
        points.y.push_back(y + 0.0);
        // Levels as the image readers scale them: a correctly rounded level / 255 (or 65535).
        for (uint32_t k = 0; k < points.channels; ++k)
            points.values.push_back(scale == 1.0 ? float(colour[k] + 0.0) : float(colour[k]) / float(scale));
    }
    return points;
}

}  // namespace ddt
