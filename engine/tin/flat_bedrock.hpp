#pragma once
// A flat bedrock under a whole terrain: the non-erodible floor of a sandbox of even depth.

#include "tin/tin.hpp"

namespace sandtin {

/// Puts the bedrock of every vertex at `z` metres, or at its surface where that lies lower (the
/// bedrock never stands above the sand). Throws std::invalid_argument when `z` is not finite.
void lay_flat_bedrock(Tin& tin, double z);

}  // namespace sandtin
