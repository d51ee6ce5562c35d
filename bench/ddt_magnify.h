// DDT for the protocol tables: one prepare and optimize per input, then the plain surface
// rendered, then the consistent reconstruction (core/image/reconstruct.h) under the degradation
// model of the realised factors rendered from the same mesh. Untimed: Tables 1–2 time DDT.
#pragma once

#include <optional>
#include <string>

#include "backend.h"
#include "methods.h"

namespace bench {

struct DdtOutputs {
    std::optional<ddt::Image> plain;
    std::optional<ddt::Image> consistent;
    std::optional<ddt::Image> fallback;  // the consistent surface with the convolution fallback
    std::string consistent_error;  // why `consistent` is missing when it was asked for
};

// `low` magnified to width × height by `backend`: the plain surface if `plain`, the
// consistent one assuming `assume` if `consistent`, and that one blended by the convolution
// fallback (core/image/convolution_fallback.h) if `fallback`. A backend whose reconstruct
// throws UserError leaves `consistent` and `fallback` empty with the message.
DdtOutputs magnifyWithDdt(ddt::Backend& backend, const ddt::Image& low, uint32_t width, uint32_t height, bool plain,
                          bool consistent, ddt::AssumedKernel assume = ddt::AssumedKernel::mixed,
                          bool fallback = false);

// "" when `method`'s backend can reconstruct (tried on a small image), else the reason.
std::string consistentUnavailableReason(const DdtMethod& method);

}  // namespace bench
