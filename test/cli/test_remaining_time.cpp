// The time-left estimate: from finished images in a batch, and from finished tiles while the
// first (or only) image is processed in tiles.
#include <catch2/catch.hpp>

#include "reporter.h"

namespace {

ddt::RunCounts counts(size_t total, size_t done, size_t skipped, size_t failed, double elapsed_s) {
    ddt::RunCounts result;
    result.total = total;
    result.done = done;
    result.skipped = skipped;
    result.failed = failed;
    result.elapsed_s = elapsed_s;
    return result;
}

}  // namespace

TEST_CASE("remaining time: unknown until an image or a tile is finished") {
    CHECK(ddt::remainingSeconds(counts(3, 0, 0, 0, 5.0), std::nullopt) == -1.0);
    CHECK(ddt::remainingSeconds(counts(1, 0, 0, 0, 5.0), ddt::TiledImageProgress{5.0, 0, 4}) == -1.0);
}

TEST_CASE("remaining time: finished images give the average for each image left") {
    // 2 done and 1 failed in 30 s: 10 s each; the skipped one costs nothing.
    CHECK(ddt::remainingSeconds(counts(7, 2, 1, 1, 30.0), std::nullopt) == Approx(30.0));
    CHECK(ddt::remainingSeconds(counts(4, 3, 1, 0, 30.0), std::nullopt) == Approx(0.0));
}

TEST_CASE("remaining time: an image in tiles goes by its own tiles") {
    // One image, 1 of 4 tiles done in 6 s: 3 tiles at 6 s.
    CHECK(ddt::remainingSeconds(counts(1, 0, 0, 0, 7.0), ddt::TiledImageProgress{6.0, 1, 4}) == Approx(18.0));
    // The first of three images, 2 of 4 tiles in 10 s: 10 s more for it, and 20 s for each other.
    CHECK(ddt::remainingSeconds(counts(3, 0, 0, 0, 11.0), ddt::TiledImageProgress{10.0, 2, 4}) == Approx(50.0));
    // After finished images, the others take their average (12 s); this one its tiles' pace.
    CHECK(ddt::remainingSeconds(counts(4, 2, 0, 0, 24.0), ddt::TiledImageProgress{9.0, 3, 4}) == Approx(3.0 + 12.0));
    // All its tiles done (writing): only the other images are left.
    CHECK(ddt::remainingSeconds(counts(2, 1, 0, 0, 20.0), ddt::TiledImageProgress{8.0, 4, 4}) == Approx(0.0));
}
