#pragma once
/// \file ValidationData.h
/// The measured data of validation/data/, embedded in the binary at build time
/// (cmake/EmbedValidationData.cmake), so a study runs from any folder and no source path is
/// compiled into the program.

namespace gale::validation {

/// The text of the embedded file `name` (its file name in validation/data/, e.g.
/// "cao-tamura-2006-ridge.csv"), or nullptr if no such file was embedded.
const char* embeddedData(const char* name);

}  // namespace gale::validation
