#include "tin/flat_bedrock.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandtin {

void lay_flat_bedrock(Tin& tin, double z) {
    if (!std::isfinite(z)) throw std::invalid_argument("bedrock: the height is not finite");
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t i = 0; i < va.size(); ++i) {
        if (va.alive[i]) tin.set_bedrock(VertexId{i}, std::min(z, va.height[i]));
    }
}

}  // namespace sandtin
