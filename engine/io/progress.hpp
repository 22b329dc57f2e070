#pragma once
// Progress of long engine work (a heightmap import, an export, a script run), reported to
// whoever shows it: the CLI draws a line on a terminal (editor/cli/progress_line.hpp). The
// engine never prints, and knows nothing of who listens.
//
// Contract for every function that takes a ProgressCallback:
//  - fractions lie in [0, 1] and never decrease; the last call, when the work completes,
//    reports exactly 1;
//  - calls are made on the calling thread, between pieces of work, a few hundred times at most
//    for the whole job (not once per sample or per vertex);
//  - an empty callback costs a branch: nothing is computed for it;
//  - the work and its result are the same with or without a callback;
//  - the callback may throw to stop the work (Cancelled, io/cancellation.hpp): the exception
//    passes through and the function leaves no partial result (see that header).

#include <algorithm>
#include <functional>
#include <string_view>

namespace sandtin {

struct Progress {
    double fraction = 0.0;  ///< of the whole job, in [0, 1]
    /// What the work does now ("refining the TIN", "operation 3 of 10 (stroke)"). Valid only
    /// during the call: a listener that keeps it copies it.
    std::string_view stage;
};

using ProgressCallback = std::function<void(const Progress&)>;

/// The callback for one part of a larger job: the part's fractions 0..1 are reported as
/// from..to of the whole, its stages as they are. Empty when `whole` is, so the part stays as
/// cheap as without progress.
inline ProgressCallback progress_part(const ProgressCallback& whole, double from, double to) {
    if (!whole) return {};
    return [whole, from, to](const Progress& p) {
        whole({from + (to - from) * std::clamp(p.fraction, 0.0, 1.0), p.stage});
    };
}

}  // namespace sandtin
