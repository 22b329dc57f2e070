#pragma once
// The one bound on heights every room shares (the TIN, scripts, importers, the haptic protocol).

namespace sandtin {

/// The largest height magnitude a terrain holds (m): the domain's largest side. Beyond it,
/// volumes and areas leave the range where they are computed exactly enough, and meshes the
/// range of the 32-bit floats their files store. Inputs (scripts, options, imported
/// heightmaps, haptic poses) are checked against it.
inline constexpr double kMaxHeight = 1e9;

}  // namespace sandtin
