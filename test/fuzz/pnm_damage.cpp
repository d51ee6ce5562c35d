// PNM (P1-P6) and PFM: a text header of whitespace-separated numbers, with comments, then
// the samples (as text for P1-P3). The numbers are replaced by text that parsers of decimal
// numbers get wrong: signs, overflow, fractions, letters, nothing.
#include <algorithm>
#include <cctype>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

struct Token {
    size_t begin, end;
};

bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// Width, height and maxval (or PFM's scale; none for bitmaps), after the 2-byte magic.
std::vector<Token> headerTokens(const std::string& file) {
    const bool bitmap = file.size() > 1 && (file[1] == '1' || file[1] == '4');
    const size_t count = bitmap ? 2 : 3;
    std::vector<Token> tokens;
    size_t at = 2;
    while (tokens.size() < count && at < file.size()) {
        if (file[at] == '#') {
            while (at < file.size() && file[at] != '\n') ++at;
        } else if (isSpace(file[at])) {
            ++at;
        } else {
            const size_t begin = at;
            while (at < file.size() && !isSpace(file[at]) && file[at] != '#') ++at;
            tokens.push_back({begin, at});
        }
    }
    return tokens;
}

bool isText(const std::string& file) { return file.size() > 1 && file[0] == 'P' && file[1] >= '1' && file[1] <= '3'; }
bool isPfm(const std::string& file) { return file.size() > 1 && file[0] == 'P' && (file[1] == 'F' || file[1] == 'f'); }

std::string replaceToken(std::string& file, const Token& token, const char* name, const std::string& text) {
    const std::string old = file.substr(token.begin, token.end - token.begin);
    file.replace(token.begin, token.end - token.begin, text);
    return std::string(name) + " '" + old + "' -> '" + text.substr(0, 24) + (text.size() > 24 ? "…" : "") + "'";
}

std::string damageSize(std::string& file, Random& random) {
    const std::vector<Token> tokens = headerTokens(file);
    if (tokens.size() < 2) return "no size in the header";
    const size_t index = random.below(2);
    const uint64_t current = std::strtoull(file.c_str() + tokens[index].begin, nullptr, 10);
    return replaceToken(file, tokens[index], index ? "height" : "width", badNumberText(random, current));
}

std::string damagePixelFormat(std::string& file, Random& random) {
    const std::vector<Token> tokens = headerTokens(file);
    if (tokens.size() == 3 && random.percent(65)) {
        if (isPfm(file)) {
            const char* scales[] = {"0", "-0", "1", "-1", "nan", "inf", "-inf", "1e308", "1e-45", "x", "-1.0e", ""};
            return replaceToken(file, tokens[2], "PFM scale", scales[random.below(std::size(scales))]);
        }
        const char* maxvals[] = {"0", "1", "2", "255", "256", "65535", "65536", "-1", "4294967295", "abc", "3"};
        return replaceToken(file, tokens[2], "maxval", maxvals[random.below(std::size(maxvals))]);
    }
    const char* magics[] = {"P1", "P2", "P3", "P4", "P5", "P6", "P7", "P0", "P8", "PF", "Pf", "pf", "PX"};
    const std::string magic = magics[random.below(std::size(magics))];
    const std::string old = file.substr(0, 2);
    file.replace(0, 2, magic);
    return "magic " + old + " -> " + magic;
}

std::string damageStructure(std::string& file, Random& random) {
    const std::vector<Token> tokens = headerTokens(file);
    if (tokens.empty()) return "no header";
    const Token& token = random.pick(tokens);
    switch (random.below(6)) {
        case 0: {
            const std::string comments[] = {"#\n", "# comment\n", "#" + std::string(10000, 'c') + "\n",
                                            "#no newline to the end"};
            const std::string comment = comments[random.below(std::size(comments))];
            const size_t at = random.percent(50) ? token.end : token.begin + random.below(token.end - token.begin + 1);
            file.insert(at, comment);
            return "comment of " + std::to_string(comment.size()) + " bytes at " + std::to_string(at);
        }
        case 1: {
            // The whitespace after a token: none (tokens run together), or other or more.
            size_t end = token.end;
            while (end < file.size() && isSpace(file[end]) && end - token.end < 8) ++end;
            const std::string spaces[] = {"", "\t", "\r\n", "  \n\n", std::string(300, ' ')};
            const std::string space = spaces[random.below(std::size(spaces))];
            file.replace(token.end, end - token.end, space);
            return "whitespace after a header number -> " + std::to_string(space.size()) + " characters";
        }
        case 2: file.erase(token.begin, token.end - token.begin); return "a header number removed";
        case 3:
            file.insert(token.end, ' ' + file.substr(token.begin, token.end - token.begin));
            return "a header number repeated";
        case 4: {
            // A PAM-style header (P7), which the reader does not take.
            file = "P7\nWIDTH 4\nHEIGHT " + badNumberText(random, 4) + "\nDEPTH 3\nMAXVAL 255\nTUPLTYPE RGB\nENDHDR\n" +
                   file.substr(tokens.back().end);
            return "PAM header";
        }
        default:
            file.insert(tokens.back().end, random.bytes(random.between(1, 8)));
            return "random bytes after the header";
    }
}

std::string damageStream(std::string& file, Random& random) {
    const std::vector<Token> tokens = headerTokens(file);
    if (tokens.empty()) return "no header";
    const size_t data = std::min(file.size(), tokens.back().end + 1);
    if (data >= file.size()) return "no samples";
    if (isText(file) && random.percent(70)) {
        // A sample of text: negative, too large, not a number, nothing.
        const std::string samples[] = {"-1", "256", "65536", "99999999999999999999", "x", "", "1.5", "2"};
        size_t at = data + random.below(file.size() - data);
        while (at < file.size() && isSpace(file[at])) ++at;
        size_t end = at;
        while (end < file.size() && !isSpace(file[end])) ++end;
        const std::string sample = samples[random.below(std::size(samples))];
        file.replace(at, end - at, sample);
        return "sample at " + std::to_string(at) + " -> '" + sample + "'";
    }
    switch (random.below(3)) {
        case 0: {
            const size_t at = data + random.below(file.size() - data);
            file.resize(at);
            return "samples cut at " + std::to_string(at);
        }
        case 1: {
            file += random.bytes(random.between(1, 2000));
            return "bytes after the samples";
        }
        default: {
            // In PFM: NaN and infinities (ddtup refuses them); elsewhere, values above maxval.
            const size_t at = data + random.below(file.size() - data),
                         count = std::min<size_t>(file.size() - at, 4 * random.between(1, 4));
            const std::string values[] = {le(4, 0x7FC00000), le(4, 0x7F800000), le(4, 0xFF800000),
                                          std::string(4, '\xFF')};
            std::string bytes;
            while (bytes.size() < count) bytes += values[random.below(std::size(values))];
            file.replace(at, count, bytes.substr(0, count));
            return std::to_string(count) + " sample bytes set to NaN, infinity or all ones";
        }
    }
}

}  // namespace

std::string damagePnm(std::string& file, DamageKind kind, Random& random) {
    if (file.size() < 3) return "not a PNM file";
    switch (kind) {
        case DamageKind::Size: return damageSize(file, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, random);
        case DamageKind::Structure: return damageStructure(file, random);
        default: return damageStream(file, random);
    }
}

}  // namespace fuzz
