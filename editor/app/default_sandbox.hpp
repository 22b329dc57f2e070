#pragma once
// The scene a new document starts from.

#include "tin/tin.hpp"

namespace sandtin::editor {

/// A new sandbox: 1 m x 1 m of sand 2 to 10 cm deep over a flat bedrock, with dunes, ripples
/// and a band of moist sand along the south edge (default_sandbox.cpp).
Tin default_sandbox();

}  // namespace sandtin::editor
