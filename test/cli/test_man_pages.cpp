// The man pages help2man writes at build time (end of CMakeLists.txt). Without help2man there
// are none, DDTUP_MAN_PAGES is not defined, and this file has no tests.
#include <catch2/catch.hpp>

#ifdef DDTUP_MAN_PAGES

#include <cstdlib>
#include <string>
#include <vector>

#include "run_ddtup.h"
#include "temp_folder.h"

namespace {

const std::string kPages = DDTUP_MAN_PAGES;

// The page as groff lays it out for a terminal, with its macro warnings in `warnings`
// ("" with an empty `warnings` where groff is not installed).
std::string render(const std::string& page, std::string& warnings) {
    if (std::system("command -v groff >/dev/null") != 0) {
        WARN("groff is not installed: " << page << " not rendered");
        return "";
    }
    TempFolder folder;
    const std::string command = "groff -k -man -Tutf8 -wmac -P-cbou '" + page + "' >'" + (folder / "text") + "' 2>'" +
                                (folder / "warnings") + "'";
    REQUIRE(std::system(command.c_str()) == 0);
    warnings = readFile(folder / "warnings");
    return readFile(folder / "text");
}

// Each heading is in the page's source, and in the rendered text where groff exists.
void requireSections(const std::string& page, const std::vector<std::string>& headings) {
    const std::string source = readFile(page);
    std::string warnings;
    const std::string text = render(page, warnings);
    CHECK(warnings.empty());
    for (const std::string& heading : headings) {
        const bool one_word = heading.find(' ') == std::string::npos;
        CHECK_THAT(source, Catch::Contains(".SH " + (one_word ? heading : "\"" + heading + "\"") + "\n"));
        if (!text.empty()) CHECK_THAT(text, Catch::Contains("\n" + heading + "\n"));
    }
}

}  // namespace

TEST_CASE("man pages: ddtup.1 has the options from --help and the sections from docs/ddtup.h2m") {
    requireSections(kPages + "/ddtup.1",
                    {"NAME", "SYNOPSIS", "OPTIONS", "EXIT STATUS", "PROGRESS JSON", "TILING AND MEMORY", "MESHES", "VOLUMES",
                     "EXAMPLES"});
    CHECK_THAT(readFile(kPages + "/ddtup.1"), Catch::Contains("scale"));
}

TEST_CASE("man pages: ddtup-batch.1 has the options from -h") {
    requireSections(kPages + "/ddtup-batch.1", {"NAME", "SYNOPSIS", "OPTIONS", "ENVIRONMENT", "EXAMPLES", "SEE ALSO"});
    CHECK_THAT(readFile(kPages + "/ddtup-batch.1"), Catch::Contains("sshloginfile"));
}

#endif
