#include "io/session_keeper.hpp"

#include <atomic>
#include <utility>

namespace sandtin {

namespace detail {

struct KeptTerrain {
    TinSnapshot terrain;
    /// A source handed out still holds the copy: the frame must not write to it. Set by the
    /// frame; cleared, with release, by the thread that copied it or dropped the source.
    std::atomic<bool> out{false};
};

}  // namespace detail

namespace {

/// The kept copy lent to one source: given back once, after the copy or when the source is
/// dropped uncalled.
class Loan {
  public:
    explicit Loan(std::shared_ptr<detail::KeptTerrain> kept) : kept_(std::move(kept)) {}
    ~Loan() { give_back(); }
    Loan(const Loan&) = delete;
    Loan& operator=(const Loan&) = delete;
    const TinSnapshot& terrain() const { return kept_->terrain; }
    void give_back() {
        if (given_back_) return;
        given_back_ = true;
        kept_->out.store(false, std::memory_order_release);
    }

  private:
    std::shared_ptr<detail::KeptTerrain> kept_;
    bool given_back_ = false;
};

void append(std::vector<IdRange>& to, const std::vector<IdRange>& ranges) {
    to.insert(to.end(), ranges.begin(), ranges.end());
}

}  // namespace

SessionKeeper::SessionKeeper(Tin& tin)
    : tin_(tin), changes_(tin), kept_(std::make_shared<detail::KeptTerrain>()) {
    changes_.take();  // "everything": the copy below is of everything
    kept_->terrain = tin.snapshot();
}

SessionKeeper::~SessionKeeper() = default;

void SessionKeeper::follow() {
    const ChangeSet taken = changes_.take();
    append(pending_.vertices, taken.vertices);
    append(pending_.triangles, taken.triangles);
    if (pending_.empty() || kept_->out.load(std::memory_order_acquire)) return;
    tin_.copy_changes_into(kept_->terrain, pending_);
    pending_ = ChangeSet{};
}

SessionSource SessionKeeper::hand_out(Generation next_generation, std::string metadata_json) {
    follow();
    if (kept_->out.load(std::memory_order_acquire)) {
        // The writer still holds the copy (it has not copied it yet): the frame copies the
        // terrain itself rather than wait.
        ++whole_copies_;
        auto whole = std::make_shared<Session>();
        whole->terrain = tin_.snapshot();
        whole->next_generation = next_generation;
        whole->metadata_json = std::move(metadata_json);
        return [whole] { return std::move(*whole); };
    }
    // Capacities that grew with nothing born in the new ids, and the lists, which the journal
    // does not name: the copy is then what Tin::snapshot() would give.
    tin_.copy_changes_into(kept_->terrain, ChangeSet{});
    tin_.copy_lists_into(kept_->terrain);
    // Handed over through the writer's queue (a mutex): the writer sees the copy as it is now.
    kept_->out.store(true, std::memory_order_relaxed);
    auto loan = std::make_shared<Loan>(kept_);
    return [loan, next_generation, metadata = std::move(metadata_json)] {
        Session s;
        s.terrain = loan->terrain();
        s.next_generation = next_generation;
        s.metadata_json = metadata;
        loan->give_back();
        return s;
    };
}

}  // namespace sandtin
