// Where an output file goes, for images and meshes alike: the path checked before any work,
// a temporary file beside it that takes the bytes, and the rename into place once all of
// them are written, so that a failure never leaves a partial file under the output's name.
#pragma once

#include <memory>
#include <string>

#include "temp_files.h"

namespace ddt {

// Refuses outputs that are not a plain replaceable file in an existing folder: throws
// UserError("PATH: reason").
void checkOutputPath(const std::string& path);

// The temporary file an output is written to: a hidden sibling of `path`, so the final rename
// stays within one file system, or for standard output ("-") one in $TMPDIR. Throws
// UserError with the system's reason when the folder is not writable.
std::unique_ptr<TempFile> createTempFile(const std::string& path);

// Renames the finished `temp` to `path`; throws UserError("NAME: reason") on failure.
void moveIntoPlace(TempFile& temp, const std::string& path, const std::string& name);

}  // namespace ddt
