#include "io/export_palette.hpp"

namespace sandtin {

MaterialColours export_palette(const MaterialTable& materials) {
    MaterialColours palette;
    palette.wet_factor = static_cast<double>(kWetReflectance);
    for (const Material& m : materials.all()) {
        palette.colours.push_back({static_cast<double>(m.colour[0]),
                                   static_cast<double>(m.colour[1]),
                                   static_cast<double>(m.colour[2])});
    }
    return palette;
}

}  // namespace sandtin
