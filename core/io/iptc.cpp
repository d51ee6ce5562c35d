#include "iptc.h"

#include <algorithm>
#include <string_view>

#include "attribute_text.h"

namespace ddt {

namespace {

// An IIM dataset of record 2 and the attributes that give it: an "IPTC:" name, and for a few
// a plain name that gives a second record of the same dataset.
struct IimDataset {
    int number;
    const char* name;
    const char* other_name;  // or null
    bool repeatable;         // one record per ';'-separated part
};

const IimDataset kDatasets[] = {
    {3, "IPTC:ObjectTypeReference", nullptr, false},
    {4, "IPTC:ObjectAttributeReference", nullptr, true},
    {5, "IPTC:ObjectName", nullptr, false},
    {7, "IPTC:EditStatus", nullptr, false},
    {10, "IPTC:Urgency", nullptr, false},
    {12, "IPTC:SubjectReference", nullptr, true},
    {15, "IPTC:Category", nullptr, false},
    {20, "IPTC:SupplementalCategories", nullptr, true},
    {22, "IPTC:FixtureIdentifier", nullptr, false},
    {25, "Keywords", nullptr, true},
    {26, "IPTC:ContentLocationCode", nullptr, true},
    {27, "IPTC:ContentLocationName", nullptr, true},
    {30, "IPTC:ReleaseDate", nullptr, false},
    {35, "IPTC:ReleaseTime", nullptr, false},
    {37, "IPTC:ExpirationDate", nullptr, false},
    {38, "IPTC:ExpirationTime", nullptr, false},
    {40, "IPTC:Instructions", nullptr, false},
    {45, "IPTC:ReferenceService", nullptr, true},
    {47, "IPTC:ReferenceDate", nullptr, false},
    {50, "IPTC:ReferenceNumber", nullptr, true},
    {55, "IPTC:DateCreated", nullptr, false},
    {60, "IPTC:TimeCreated", nullptr, false},
    {62, "IPTC:DigitalCreationDate", nullptr, false},
    {63, "IPTC:DigitalCreationTime", nullptr, false},
    {65, "IPTC:OriginatingProgram", "Software", false},
    {70, "IPTC:ProgramVersion", nullptr, false},
    {80, "IPTC:Creator", "Artist", true},
    {85, "IPTC:AuthorsPosition", nullptr, true},
    {90, "IPTC:City", nullptr, false},
    {92, "IPTC:Sublocation", nullptr, false},
    {95, "IPTC:State", nullptr, false},
    {100, "IPTC:CountryCode", nullptr, false},
    {101, "IPTC:Country", nullptr, false},
    {103, "IPTC:TransmissionReference", nullptr, false},
    {105, "IPTC:Headline", nullptr, false},
    {110, "IPTC:Provider", nullptr, false},
    {115, "IPTC:Source", nullptr, false},
    {116, "IPTC:CopyrightNotice", "Copyright", false},
    {118, "IPTC:Contact", nullptr, false},
    {120, "IPTC:Caption", "ImageDescription", false},
    {121, "IPTC:LocalCaption", nullptr, false},
    {122, "IPTC:CaptionWriter", nullptr, false},
    {184, "IPTC:JobID", nullptr, false},
    {185, "IPTC:MasterDocumentID", nullptr, false},
    {186, "IPTC:ShortDocumentID", nullptr, false},
    {187, "IPTC:UniqueDocumentID", nullptr, false},
    {188, "IPTC:OwnerID", nullptr, false},
    {221, "IPTC:Prefs", nullptr, false},
    {225, "IPTC:ClassifyState", nullptr, false},
    {228, "IPTC:SimilarityIndex", nullptr, false},
    {230, "IPTC:DocumentNotes", nullptr, false},
    {231, "IPTC:DocumentHistory", nullptr, false},
};

std::string_view stripped(std::string_view text) {
    constexpr std::string_view kSpace = " \t\n\r\f\v";
    const size_t first = text.find_first_not_of(kSpace);
    if (first == std::string_view::npos) return {};
    return text.substr(first, text.find_last_not_of(kSpace) - first + 1);
}

// One record: 0x1C, record 2, the dataset, a big-endian 16-bit size and the data. Data is cut
// one byte short of the 16-bit limit, as OpenImageIO cuts it; an empty value gets no size.
void addRecord(int dataset, std::string_view data, std::string& out) {
    out += char(0x1C);
    out += char(0x02);
    out += char(dataset);
    if (data.empty()) return;
    const size_t size = std::min<size_t>(data.size(), 0xFFFF - 1);
    out += char(size >> 8);
    out += char(size & 0xFF);
    out += data.substr(0, size);
}

}  // namespace

std::string encodeIptc(const ImageAttributes& attributes) {
    std::string out;
    for (const IimDataset& dataset : kDatasets) {
        if (const ImageAttribute* attribute = attributes.find(dataset.name)) {
            const std::string text = attributeText(*attribute);
            if (dataset.repeatable) {
                for (size_t start = 0; start <= text.size();) {
                    size_t end = std::min(text.find(';', start), text.size());
                    std::string_view part = stripped(std::string_view(text).substr(start, end - start));
                    if (!part.empty()) addRecord(dataset.number, part, out);
                    start = end + 1;
                }
            } else {
                addRecord(dataset.number, text, out);
            }
        }
        if (dataset.other_name)
            if (const ImageAttribute* attribute = attributes.find(dataset.other_name))
                addRecord(dataset.number, attributeText(*attribute), out);
    }
    return out;
}

}  // namespace ddt
