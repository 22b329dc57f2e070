#pragma once
// Cancelling long engine work (a heightmap import, an export): whoever shows the progress
// (io/progress.hpp) may also offer a Cancel button. The listener sets a CancellationToken;
// the work looks at it where it reports progress, between pieces, and stops there by throwing
// Cancelled, so a cancelled job leaves what any failure leaves: nothing.
//
// Contract, for every function that takes a ProgressCallback:
//  - the callback may throw; the function then propagates the exception, having returned no
//    result and having changed nothing of its caller's (an import returns no TIN, an export
//    writes its files only after its last report short of 1, so a cancelled export leaves no
//    new file and every old one as it was);
//  - cancellable() checks the token before each report short of 1: the report of 1, made when
//    the work is complete, never throws (what is done is done, and the caller keeps it).
//
// The token is read and written from any thread: the work runs on a worker, the Cancel
// button is on the UI thread.

#include <atomic>
#include <stdexcept>
#include <utility>

#include "io/progress.hpp"

namespace sandtin {

/// The outcome of work that was cancelled: not a failure, and callers catch it before
/// std::exception to say so.
class Cancelled : public std::runtime_error {
  public:
    Cancelled() : std::runtime_error("cancelled") {}
};

class CancellationToken {
  public:
    /// Asks the work to stop at its next check. Idempotent; never undone.
    void cancel() noexcept { cancelled_.store(true, std::memory_order_release); }
    bool cancelled() const noexcept { return cancelled_.load(std::memory_order_acquire); }
    void throw_if_cancelled() const {
        if (cancelled()) throw Cancelled();
    }

  private:
    std::atomic<bool> cancelled_{false};
};

/// `progress` (which may be empty) with the token checked first at every report short of 1:
/// once `token` is cancelled, the work's next report throws Cancelled instead of being heard.
/// The token must outlive the work.
inline ProgressCallback cancellable(ProgressCallback progress, const CancellationToken& token) {
    return [progress = std::move(progress), &token](const Progress& p) {
        if (p.fraction < 1.0) token.throw_if_cancelled();
        if (progress) progress(p);
    };
}

}  // namespace sandtin
