// The main of every test executable: Catch2's own, plus `--list-labels`, which prints one line
// per test that runs by default, "NAME<tab>SOURCE FILE<tab>TAG,TAG…", for label_tests.cmake
// to turn into CTest labels (Catch2 v2's CMake discovery sets no labels, and its listings wrap
// long names).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstring>
#include <string>

namespace {

int listLabels() {
    for (const Catch::TestCase& test : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
        if (test.isHidden()) continue;
        // Catch.cmake's discovery cuts a name at ';', and the fields here are tab-separated.
        if (test.name.find_first_of(";\t") != std::string::npos) {
            std::fprintf(stderr, "a test name with ';' or a tab, which CTest cannot carry: %s\n", test.name.c_str());
            return 1;
        }
        std::string tags;
        for (const std::string& tag : test.tags) tags += (tags.empty() ? "" : ",") + tag;
        std::printf("%s\t%s\t%s\n", test.name.c_str(), test.lineInfo.file, tags.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char* argv[]) {
    if (argc == 2 && std::strcmp(argv[1], "--list-labels") == 0) return listLabels();
    return Catch::Session().run(argc, argv);
}
