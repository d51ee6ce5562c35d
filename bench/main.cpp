// ddtup-bench: reproduces the paper's Tables 1–3 and Fig. 13 in one command.
#include <iostream>

#include "bench_cli.h"
#include "bench_run.h"
#include "user_error.h"

int main(int argc, char** argv) {
    int exit_code = 0;
    std::optional<bench::BenchOptions> options = bench::parseBenchCommandLine(argc, argv, exit_code);
    if (!options) return exit_code;
    try {
        bench::runBench(*options);
        return 0;
    } catch (const ddt::UserError& error) {
        std::cerr << "ddtup-bench: " << error.what() << "\n";
        return 1;
    }
}
