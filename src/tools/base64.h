// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <string>
#include <string_view>

namespace freeform_inspection {

/// @brief Standard base64 (RFC 4648, with '=' padding) of `bytes`.
std::string base64Encode(std::string_view bytes);

/// @brief A data URI holding `bytes`, e.g. dataUri("image/png", png) for an inline <img>.
std::string dataUri(std::string_view mime_type, std::string_view bytes);

}  // namespace freeform_inspection
