// What became of one damaged input: the report's columns.
#pragma once

namespace fuzz {

enum class Outcome {
    Accepted,       // decoded, magnified, output written
    Refused,        // failed with a "FILE: reason" message, nothing left behind
    Crash,          // the process died of a signal (or aborted)
    Hang,           // the process ran past its time limit
    Sanitizer,      // AddressSanitizer, UndefinedBehaviorSanitizer or LeakSanitizer reported
    SilentRefusal,  // failed without an error naming it, or done without an output
    LeftFile,       // failed but left its output or a .NAME.ddtup* temporary file
    InternalError,  // failed with "internal error" (exit code 4): a bug in ddtup
};
constexpr Outcome kOutcomes[] = {Outcome::Accepted,  Outcome::Refused,       Outcome::Crash,    Outcome::Hang,
                                 Outcome::Sanitizer, Outcome::SilentRefusal, Outcome::LeftFile, Outcome::InternalError};
constexpr int kOutcomeCount = 8;

// Short column heading: "accepted", "silent refusal", …
const char* outcomeName(Outcome outcome);
// Everything but Accepted and Refused is a fault, and must be 0.
inline bool isFault(Outcome outcome) { return outcome != Outcome::Accepted && outcome != Outcome::Refused; }

}  // namespace fuzz
