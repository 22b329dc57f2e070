#include "tin/detail/impl_helpers.hpp"

#include <sstream>

namespace sandtin::detail {

std::string describe(Vec2 p) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}

void require_inside(const Rect& domain, Vec2 p, const char* what) {
    // Messages are built only on failure: this runs once per inserted point.
    if (!is_finite(p)) {
        throw std::invalid_argument(std::string(what) + ": coordinates " + describe(p) +
                                    " are not finite");
    }
    if (!domain.contains(p)) {
        throw std::invalid_argument(std::string(what) + ": point " + describe(p) +
                                    " lies outside the terrain domain [" + describe(domain.min) +
                                    ", " + describe(domain.max) + "]");
    }
}

}  // namespace sandtin::detail
