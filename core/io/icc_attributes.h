// The attributes OpenImageIO 2.4 makes of an ICC profile's header and text tags
// ("ICCProfile:color_space", "ICCProfile:profile_description", …), beside the profile itself.
#pragma once

#include <cstdint>
#include <vector>

#include "image_attributes.h"

namespace ddt {

// Sets them as OpenImageIO's decode_icc_profile does, in its order; a profile it finds
// damaged keeps what was set before the damage, as there.
void addIccAttributes(const std::vector<uint8_t>& profile, ImageAttributes& attributes);

}  // namespace ddt
