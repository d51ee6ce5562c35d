#include "oiio_codec.h"


namespace ddt {

std::string firstLine(std::string message) {
    size_t end = message.find('\n');
    if (end != std::string::npos) message.resize(end);
    while (!message.empty() && (message.back() == ' ' || message.back() == '.')) message.pop_back();
    return message.empty() ? "unknown error" : message;
}

std::string globalError() { return OIIO::has_error() ? OIIO::geterror() : std::string(); }

SampleType sampleTypeOf(OIIO::TypeDesc format) {
    switch (format.basetype) {
        case OIIO::TypeDesc::UINT8:
        case OIIO::TypeDesc::INT8:
            return SampleType::UInt8;
        case OIIO::TypeDesc::UINT16:
        case OIIO::TypeDesc::INT16:
            return SampleType::UInt16;
        case OIIO::TypeDesc::HALF:
            return SampleType::Half;
        default:
            return SampleType::Float;
    }
}

OIIO::TypeDesc typeDescOf(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return OIIO::TypeDesc::UINT8;
        case SampleType::UInt16:
            return OIIO::TypeDesc::UINT16;
        case SampleType::Half:
            return OIIO::TypeDesc::HALF;
        case SampleType::Float:
            break;
    }
    return OIIO::TypeDesc::FLOAT;
}

}  // namespace ddt
