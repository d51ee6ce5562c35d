// The exit codes, documented in the README and the man page. Scripts rely on them: keep them.
#pragma once

namespace ddt {

enum ExitCode : int {
    kExitDone = 0,         // every image done (or skipped with --skip-existing)
    kExitSomeFailed = 1,   // one or more images failed; the others were done
    kExitUsage = 2,        // the command line is wrong; nothing was done
    kExitNoDevice = 3,     // no usable Vulkan device; nothing was done
    kExitInternal = 4,     // a bug in ddtup
    // Interrupted runs end by their signal: 130 for SIGINT, 143 for SIGTERM (128 + signal).
};

}  // namespace ddt
