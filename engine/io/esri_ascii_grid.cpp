#include "io/esri_ascii_grid.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace sandtin {

namespace {

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

class Cursor {
  public:
    Cursor(std::span<const std::uint8_t> bytes, const std::string& name)
        : text_(reinterpret_cast<const char*>(bytes.data()), bytes.size()), name_(name) {
        // Windows editors save text with a UTF-8 byte-order mark; it is not part of the grid.
        if (text_.starts_with(kUtf8Bom)) pos_ = kUtf8Bom.size();
    }

    /// The next whitespace-separated token (empty at the end).
    std::string_view token() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])))
            ++pos_;
        return text_.substr(start, pos_ - start);
    }
    /// Peeks at the next token without consuming it.
    std::string_view peek() {
        const std::size_t pos = pos_;
        const std::size_t line = line_;
        const std::string_view t = token();
        pos_ = pos;
        line_ = line;
        return t;
    }
    std::size_t line() const { return line_; }
    /// Bytes not yet read.
    std::size_t remaining() const { return text_.size() - pos_; }
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(name_ + ": line " + std::to_string(line_) + ": " + what);
    }

  private:
    std::string_view text_;
    std::string name_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
};

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

/// Parses a number the way the grid writes it: an optional sign, digits, "nan", "inf".
std::optional<double> parse_double(std::string_view t) {
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size() || t.empty()) return std::nullopt;
    return v;
}

bool is_header_key(std::string_view t) {
    if (t.empty()) return false;
    const unsigned char c = static_cast<unsigned char>(t.front());
    const std::string l = lower(t);
    return std::isalpha(c) && l != "nan" && l != "inf" && l != "infinity";
}

}  // namespace

HeightRaster parse_esri_ascii_grid(std::span<const std::uint8_t> bytes, const std::string& name,
                                   const RasterLimits& limits, bool nonfinite_as_nodata) {
    if (bytes.empty()) throw std::runtime_error(name + ": file is empty");
    Cursor in(bytes, name);
    static const std::map<std::string, std::string> kKeys = {
        {"ncols", "ncols"},  {"nrows", "nrows"}, {"xllcorner", "x"},
        {"xllcenter", "x"},  {"xllcentre", "x"}, {"yllcorner", "y"},
        {"yllcenter", "y"},  {"yllcentre", "y"}, {"cellsize", "cellsize"},
        {"dx", "dx"},        {"dy", "dy"},       {"nodata_value", "nodata"},
        {"nodata", "nodata"}};
    std::map<std::string, double> values;
    bool x_centre = false;
    bool y_centre = false;
    while (is_header_key(in.peek())) {
        const std::string key = lower(in.token());
        const auto it = kKeys.find(key);
        if (it == kKeys.end()) {
            in.fail(
                "'" + key +
                "' is not an ESRI ASCII grid header key (expected ncols, nrows, "
                "xllcorner/xllcenter, yllcorner/yllcenter, cellsize or dx and dy, NODATA_value)");
        }
        if (values.count(it->second) != 0) in.fail("header key '" + key + "' is given twice");
        const std::string_view value_text = in.token();
        const std::optional<double> value = parse_double(value_text);
        // GDAL writes "NODATA_value nan" for a band whose no-data is NaN.
        const bool nan_nodata = it->second == "nodata" && value && std::isnan(*value);
        if (!value || (!std::isfinite(*value) && !nan_nodata)) {
            in.fail("header key '" + key + "' needs a finite number, not '" +
                    std::string(value_text) + "'");
        }
        values[it->second] = *value;
        if (it->second == "x") x_centre = key.find("cent") != std::string::npos;
        if (it->second == "y") y_centre = key.find("cent") != std::string::npos;
    }
    // GDAL writes a grid of oblong cells with dx and dy (column and row spacing) in place of
    // cellsize.
    const bool oblong = values.count("dx") != 0 || values.count("dy") != 0;
    if (oblong &&
        (values.count("cellsize") != 0 || values.count("dx") == 0 || values.count("dy") == 0)) {
        throw std::runtime_error(name +
                                 ": not an ESRI ASCII grid: give either 'cellsize' or both 'dx' "
                                 "and 'dy'");
    }
    if (oblong) values["cellsize"] = values["dx"];
    for (const char* required : {"ncols", "nrows", "x", "y", "cellsize"}) {
        if (values.count(required) == 0) {
            const std::string what = std::string(required) == "x"   ? "xllcorner or xllcenter"
                                     : std::string(required) == "y" ? "yllcorner or yllcenter"
                                                                    : required;
            throw std::runtime_error(name + ": not an ESRI ASCII grid: the header lacks '" + what +
                                     "'");
        }
    }
    for (const char* count : {"ncols", "nrows"}) {
        const double v = values[count];
        if (v < 0.0 || v != std::floor(v) || v > 4.0e9) {
            throw std::runtime_error(name + ": header key '" + count +
                                     "' must be a whole number, not " + std::to_string(v));
        }
    }
    const auto cols = static_cast<std::uint64_t>(values["ncols"]);
    const auto rows = static_cast<std::uint64_t>(values["nrows"]);
    check_raster_size(cols, rows, name, limits);
    const double cellsize = values["cellsize"];
    const double row_spacing = oblong ? values["dy"] : cellsize;
    if (!(cellsize > 0.0) || !(row_spacing > 0.0)) {
        std::ostringstream what;
        what << name << ": header key '" << (oblong ? "dx' and 'dy" : "cellsize")
             << "' must be positive, not " << cellsize;
        if (oblong) what << " and " << row_spacing;
        throw std::runtime_error(what.str());
    }
    // Without the key, ESRI's documented default of -9999 holds: files written without it
    // still mark missing cells that way. A plain value: GCC 12 misreads an optional here
    // (-Wmaybe-uninitialized). NaN as no-data makes every NaN sample missing.
    const double nodata = values.count("nodata") != 0 ? values["nodata"] : kEsriDefaultNodata;
    const bool nan_is_nodata = std::isnan(nodata);

    HeightRaster r;
    r.width = static_cast<std::uint32_t>(cols);
    r.height = static_cast<std::uint32_t>(rows);
    r.cell_size = cellsize;
    if (row_spacing != cellsize) r.cell_height = row_spacing;
    r.source_format = "esri-ascii";
    r.georeference.known = true;
    r.georeference.west = values["x"] + (x_centre ? 0.0 : 0.5 * cellsize);
    r.georeference.south = values["y"] + (y_centre ? 0.0 : 0.5 * row_spacing);
    // Each height takes a character and a separator: a file too short to hold them all is
    // refused before the raster is allocated (a 60-byte header could ask for 2 GB).
    if (in.remaining() + 1 < 2 * r.size()) {
        throw std::runtime_error(
            name + ": truncated: expected " + std::to_string(r.size()) + " heights (" +
            std::to_string(r.width) + " x " + std::to_string(r.height) + "), but only " +
            std::to_string(in.remaining()) + " bytes follow the header, too few for them");
    }
    r.heights.resize(r.size());
    bool any_nodata = false;
    std::vector<std::uint8_t> valid(r.size(), 1);
    for (std::size_t i = 0; i < r.size(); ++i) {
        const std::string_view t = in.token();
        const std::size_t col = i % r.width;
        const std::size_t row = i / r.width;
        if (t.empty()) {
            throw std::runtime_error(name + ": truncated: expected " + std::to_string(r.size()) +
                                     " heights (" + std::to_string(r.width) + " x " +
                                     std::to_string(r.height) + "), found " + std::to_string(i));
        }
        const std::optional<double> v = parse_double(t);
        if (!v) {
            in.fail("the height at row " + std::to_string(row) + ", column " + std::to_string(col) +
                    " is not a number: '" + std::string(t.substr(0, 40)) + "'");
        }
        if (*v == nodata || (std::isnan(*v) && nan_is_nodata) ||
            (!std::isfinite(*v) && nonfinite_as_nodata)) {
            valid[i] = 0;
            any_nodata = true;
            r.heights[i] = 0.0;
            continue;
        }
        if (!std::isfinite(*v)) {
            in.fail("the height at row " + std::to_string(row) + ", column " + std::to_string(col) +
                    " is not finite ('" + std::string(t) +
                    "'); declare it as NODATA_value or import with non-finite heights as no-data");
        }
        r.heights[i] = *v;
    }
    if (!in.token().empty()) {
        in.fail("more heights than ncols x nrows = " + std::to_string(r.size()));
    }
    if (any_nodata) r.valid = std::move(valid);
    return r;
}

}  // namespace sandtin
