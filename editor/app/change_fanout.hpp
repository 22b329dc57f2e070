#pragma once
// The TIN's change journal has one consumer (Tin::take_changes() hands each change out once),
// but the editor has three: the render mesh, the GPU mirror (which the GPU physics and the
// normal-map bake share) and the normal map's dirty rectangle. ChangeFanout is that single
// consumer: whoever asks first takes the journal, and every channel receives the same changes,
// merged with whatever it has not yet taken. So the mesh and the mirror always see every change
// exactly as if each were the only consumer (a range named twice is recomputed once; consumers read
// the TIN's current state).

#include <cstddef>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::editor {

/// Union of two sorted, disjoint range lists, as one sorted, disjoint, non-adjacent list.
std::vector<IdRange> union_of_ranges(const std::vector<IdRange>& a, const std::vector<IdRange>& b);

class ChangeFanout {
  public:
    enum Channel : std::size_t { Mesh = 0, Mirror = 1, NormalMap = 2, Count = 3 };

    /// `tin` must track changes and outlive the fan-out.
    explicit ChangeFanout(Tin& tin) : tin_(tin) {}

    /// Everything that changed in the TIN since this channel's previous take.
    ChangeSet take(Channel channel);

  private:
    void pull();

    Tin& tin_;
    ChangeSet pending_[Count];
};

}  // namespace sandtin::editor
