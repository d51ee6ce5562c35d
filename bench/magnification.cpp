#include "magnification.h"

#include <cstdio>

namespace bench {

std::string Magnification::name() const {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value());
    return text;
}

bool operator==(const Magnification& a, const Magnification& b) {
    return uint64_t(a.numerator) * b.denominator == uint64_t(b.numerator) * a.denominator;
}

}  // namespace bench
