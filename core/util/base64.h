// SPDX-License-Identifier: Apache-2.0
// Base64 (RFC 4648, standard alphabet, '=' padding) for binary data inside JSON files: the
// project file's depth masks. Decoding is strict: any character outside the alphabet, bad
// padding or a truncated quantum is refused, so a damaged file is reported, never half-read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

std::string encodeBase64(const std::vector<uint8_t>& bytes);
// nullopt when `text` is not valid base64.
std::optional<std::vector<uint8_t>> decodeBase64(std::string_view text);

}  // namespace artcam
