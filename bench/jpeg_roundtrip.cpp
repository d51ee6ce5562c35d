#include "jpeg_roundtrip.h"

#include "temp_files.h"
#include "image_file.h"

namespace bench {

ddt::Image jpegRoundTrip(const ddt::Image& image, int quality) {
    const ddt::TempFile file(ddt::tempFolder(), "ddtup-bench-jpeg");
    ddt::WriteOptions options;
    options.quality = quality;
    options.format = "jpg";  // the temporary file has no extension
    ddt::writeImage(file.path(), image, options);
    return ddt::readImage(file.path());
}

}  // namespace bench
