// Runs the real ddtup executable on a batch of damaged files, the way a user would
// (`ddtup f1 f2 … -o DIR`, which goes on past bad files), under the sanitizers' options,
// and judges each file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "outcome.h"
#include "process.h"

namespace fuzz {

struct RunSettings {
    std::string ddtup;              // the executable
    double seconds_per_input = 20;  // a single input taking longer hangs
};

struct BatchResult {
    ProcessResult process;
    std::string events;                    // ddtup's stderr: its JSON events
    std::string sanitizer_report;          // what the sanitizers logged, "" for nothing
    std::optional<Outcome> process_fault;  // the process crashed, hung or a sanitizer reported
    std::vector<Outcome> outcomes;         // one per input: the process fault when there was one
    std::vector<std::string> command;
    bool given_longer = false;  // runAlone ran it a second time, with more time
    bool tracer_rerun = false;  // LeakSanitizer's own tracer crashed, and the run was made again
};

// Runs ddtup on `inputs` (paths), writing into `folder`/out and logging into `folder`.
// When the process itself fails, every input gets the process's fault. A run whose only
// report is LeakSanitizer's own tracer crashing at exit ("Tracer caught signal 11", a fault
// of the leak check's thread-stopping, not a finding about ddtup; seen once in hundreds of
// runs, with OpenImageIO's threads alive at exit) is made once more, and what that run gives
// counts: a tracer that crashes twice fails the run.
BatchResult runDdtup(const RunSettings& settings, const std::vector<std::string>& inputs, const std::string& folder);

// Runs ddtup on `input` alone. One that runs out of time gets a second run with 30 times as
// long: a damaged header can claim tens of megapixels that still decode (RLE data may end
// early), which takes ddtup minutes under the sanitizers, and that is not a hang. If it then
// finishes it counts as what it is; if not, as the hang it is.
BatchResult runAlone(const RunSettings& settings, const std::string& input, const std::string& folder);

}  // namespace fuzz
