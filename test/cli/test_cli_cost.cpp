// --cost for images through the real executable: each cost reaches both backends' optimizers.
#include <catch2/catch.hpp>

#include <map>

#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

// The number after `label` in --stats' output.
double statOf(const Run& run, const std::string& label) {
    const size_t at = run.out.find(label);
    REQUIRE(at != std::string::npos);
    return std::stod(run.out.substr(at + label.size()));
}

}  // namespace

TEST_CASE("cli cost: each cost reaches the CPU and the Vulkan optimizer", "[vulkan]") {
    TempFolder work;
    const std::string input = ddt::test::testDataPath("crop32_astronaut.png");
    for (const std::string backend : {"cpu", "vulkan"}) {
        std::map<std::string, double> cost_init;
        for (const std::string cost : {"sederberg", "variance", "face-scf"}) {
            INFO(backend << " " << cost);
            const Run run = runDdtup({input, work / "out.png", "--cost", cost, "--backend", backend, "--stats", "-q"});
            REQUIRE(run.exit_code == 0);
            cost_init[cost] = statOf(run, "cost-init");
            CHECK(statOf(run, "cost-final") < cost_init[cost]);
        }
        // On a mesh of the pixel grid every triangle has area 1/2 (core/image/cost.h), so face-SCF is
        // Sederberg's cost / 3 exactly; variance is another function altogether.
        // --stats prints costs to 6 decimals, so the ratio holds to that rounding, not exactly.
        CHECK(cost_init["face-scf"] == Approx(cost_init["sederberg"] / 3).epsilon(1e-6));
        // Far apart, not within a rounding: a cost that fell back to Sederberg's would be equal.
        CHECK(cost_init["variance"] != Approx(cost_init["sederberg"]).epsilon(1e-3));
    }
}
