#include "io/heightmap_raster.hpp"

#include <cmath>
#include <stdexcept>

namespace sandtin {

std::size_t HeightRaster::nodata_count() const {
    std::size_t n = 0;
    for (std::uint8_t v : valid)
        n += v == 0 ? 1 : 0;
    return n;
}

Rect HeightRaster::domain() const {
    return {origin, position(width - 1, 0)};
}

void check_raster_size(std::uint64_t width, std::uint64_t height, const std::string& name,
                       const RasterLimits& limits) {
    if (width == 0 || height == 0) {
        throw std::runtime_error(name + ": the raster is empty (" + std::to_string(width) + " x " +
                                 std::to_string(height) + " samples)");
    }
    if (width > limits.max_width || height > limits.max_height) {
        throw std::runtime_error(name + ": a raster of " + std::to_string(width) + " x " +
                                 std::to_string(height) + " samples exceeds the limit of " +
                                 std::to_string(limits.max_width) + " x " +
                                 std::to_string(limits.max_height));
    }
    if (width < 2 || height < 2) {
        throw std::runtime_error(name + ": a raster of " + std::to_string(width) + " x " +
                                 std::to_string(height) +
                                 " samples spans no area; a terrain needs at least 2 x 2");
    }
}

void check_raster(const HeightRaster& raster, const std::string& name, const RasterLimits& limits) {
    check_raster_size(raster.width, raster.height, name, limits);
    if (!(std::isfinite(raster.cell_size) && raster.cell_size > 0.0) ||
        !(std::isfinite(raster.cell_height) && raster.cell_height >= 0.0)) {
        throw std::runtime_error(name + ": the cell size must be a positive number of metres");
    }
    if (raster.heights.size() != raster.size() ||
        (!raster.valid.empty() && raster.valid.size() != raster.size())) {
        throw std::runtime_error(name + ": the raster holds the wrong number of samples");
    }
    std::size_t valid = 0;
    for (std::size_t i = 0; i < raster.size(); ++i) {
        if (!raster.is_valid(i)) continue;
        ++valid;
        if (!std::isfinite(raster.heights[i])) {
            throw std::runtime_error(
                name + ": sample at column " + std::to_string(i % raster.width) + ", row " +
                std::to_string(i / raster.width) + " has a non-finite height (" +
                std::to_string(raster.heights[i]) + ")");
        }
    }
    if (valid == 0) throw std::runtime_error(name + ": every sample is no-data");
}

std::size_t fill_nodata(HeightRaster& raster) {
    if (raster.valid.empty()) return 0;
    const std::size_t n = raster.size();
    std::vector<std::uint8_t> done(raster.valid);
    std::vector<std::uint32_t> queue;
    queue.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (done[i]) queue.push_back(static_cast<std::uint32_t>(i));
    }
    std::size_t filled = 0;
    const std::uint32_t w = raster.width;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t i = queue[head];
        const std::uint32_t col = i % w;
        const std::uint32_t row = i / w;
        auto visit = [&](std::uint32_t j) {
            if (done[j]) return;
            done[j] = 1;
            raster.heights[j] = raster.heights[i];
            ++filled;
            queue.push_back(j);
        };
        if (col > 0) visit(i - 1);
        if (col + 1 < w) visit(i + 1);
        if (row > 0) visit(i - w);
        if (row + 1 < raster.height) visit(i + w);
    }
    return filled;
}

}  // namespace sandtin
