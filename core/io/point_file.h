// Point files (`ddtup --points FILE`): colour samples at arbitrary places, for the app to
// triangulate and magnify. CSV (point_csv.cpp) or PLY (point_ply.cpp), chosen by extension.
//
// Conventions, the same for both formats:
// - Positions in input pixels: x right, y DOWN, pixel centres at integers, as an image's pixel
//   (x, y) lies (core/image/indexed_mesh.h). Coordinates must be finite and >= 0: points lie in the
//   frame that starts at pixel centre 0; the app checks the upper bound against its frame.
// - Colours as images store them: sRGB-encoded values, straight (not premultiplied) alpha.
//   Every value must be finite; integer types are scaled to [0, 1], float ones must lie in it.
// - Nothing is merged, sorted or checked for collinearity here: the app does that with the
//   triangulation. Duplicate points come back as the file lists them.
//
// CSV (text, one point per line):
//   x,y,v        grey               x,y,r,g,b     RGB
//   x,y,v,a      grey + alpha       x,y,r,g,b,a   RGBA
// Every data line has the same number of columns (3 to 6). Fields are separated by commas,
// with optional spaces or tabs around them; numbers are read locale-independently (a decimal
// point, never a comma; exponents allowed). Lines end in LF or CRLF. Skipped: blank lines,
// lines whose first non-space character is `#`, and one header line (column names) where the
// first line that is neither has a first field that is not a number.
// The values' scale, one rule for the whole file: if every colour value is a whole number and
// any exceeds 1, they are 8-bit levels 0–255 (sample_type UInt8, value / 255), and one above
// 255 is refused; otherwise they are numbers in [0, 1] (sample_type Float), and one above 1 is
// refused. So `0,0,255,128,0` is 8-bit, `0,0,1,0.5,0` is [0, 1], and a file of only 0s and 1s
// is [0, 1] (black and white, not levels 0 and 1).
//
// PLY: ascii, binary_little_endian or binary_big_endian 1.0. From the element `vertex`:
// properties x and y (float or double; z and any others, of any scalar type, are skipped) and
// red, green, blue and optionally alpha, all of one type: uchar (/ 255, UInt8), ushort
// (/ 65535, UInt16), float or double (as they are, Float). Elements before `vertex` are
// skipped (their list properties too); those after it (faces) are not read. A file without
// red, green and blue is refused; grey is read as RGB (3 channels), as ddtup's mesh files
// store it. Coordinates are taken as input pixels with y down, like the CSV's: a mesh ddtup
// wrote (`--mesh`, core/io/mesh_file.h) is in output pixels with y up and a border ring, so
// read back as points it comes out upside down, at the output's scale.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "image.h"

namespace ddt {

// A set of colour samples at arbitrary places (`ddtup --points FILE`).
struct PointSamples {
    uint32_t channels = 0;                       // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    SampleType sample_type = SampleType::UInt8;  // what the file stored (decides the output's default depth)
    std::vector<double> x, y;                    // input pixels, x right, y down, pixel centres at integers
    std::vector<float> values;                   // `channels` per point, straight, [0, 1]

    size_t size() const { return x.size(); }
};

// The most points a file may hold: kMaxInputPixels, the largest image's pixel count. The
// triangulation numbers vertices and triangles with uint32_t, and n points make up to 2n
// triangles of three indices (6n < 2^32 needs n < 2^29.4); the memory is then of the order of
// the largest image's. A header declaring more is refused before anything is allocated.
constexpr uint64_t kMaxPoints = kMaxInputPixels;

// True if `path` ends in .csv or .ply, any case.
bool isPointFilePath(const std::string& path);

// Reads the points of a .csv or .ply file (see the top of this file). Throws
// UserError("PATH: reason"), one line, for a missing, unreadable or empty file, an unknown
// extension, and anything the parsers refuse.
PointSamples readPointFile(const std::string& path);

// The parsers, on a whole file in memory; `name` starts each UserError's message.
PointSamples parseCsvPoints(const std::string& name, std::string_view text);
PointSamples parsePlyPoints(const std::string& name, std::string_view bytes);

// What both parsers check: "" if the value may be read, else the reason.
std::string coordinateProblem(double x, double y);         // finite and >= 0
std::string colourProblem(double value, double largest);   // finite, in [0, largest]

}  // namespace ddt
