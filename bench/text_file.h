// Writing the bench's text outputs (Markdown, CSV, SVG, JSON).
#pragma once

#include <string>

namespace bench {

// Writes `content` to `path`, replacing it. Throws UserError("PATH: reason") on failure.
void writeTextFile(const std::string& path, const std::string& content);

}  // namespace bench
