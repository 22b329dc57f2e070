#pragma once
// The terrain being edited and everything whose lifetime follows it (sculpt context, physics,
// undo history), plus the default sandbox a new document starts from.

#include <chrono>
#include <filesystem>
#include <memory>

#include "erosion.hpp"
#include "history/history.hpp"
#include "io/scene_materials.hpp"
#include "io/session_file.hpp"
#include "tools/sculpt_context.hpp"

namespace sandtin::editor {

/// The terrain being edited and everything that follows its lifetime. Movable: the parts live
/// on the heap, so the history's and the physics' references to the TIN stay valid.
struct Document {
    std::filesystem::path path;  ///< empty: untitled (new, or imported from a heightmap)
    std::unique_ptr<Tin> tin;
    std::unique_ptr<SculptContext> context;
    std::unique_ptr<Erosion> physics;  ///< CPU here; the app may switch it to the GPU
    std::unique_ptr<History> history;
    MaterialTable materials = MaterialTable::presets();
    /// The metadata the terrain came with (an import record, another tool's keys); saves keep
    /// it, with the materials replaced.
    std::string metadata_json = "{}";
    bool dirty = false;
    /// An opened, imported or recovered terrain is not eroded until the artist presses Run
    /// (an elevation model would otherwise start melting as it appears); a new sandbox is.
    bool erosion_held = false;

    Document() = default;
    Document(Document&&) = default;
    /// Tears this document down (in the order its parts depend on each other) first.
    Document& operator=(Document&& other) noexcept {
        if (this != &other) {
            close();
            path = std::move(other.path);
            tin = std::move(other.tin);
            context = std::move(other.context);
            physics = std::move(other.physics);
            history = std::move(other.history);
            materials = std::move(other.materials);
            metadata_json = std::move(other.metadata_json);
            dirty = other.dirty;
            erosion_held = other.erosion_held;
        }
        return *this;
    }
    ~Document() { close(); }

    /// A document over terrain `t` with its material table (presets for a new or imported
    /// terrain) and the metadata it came with, at `p` (empty: untitled).
    static Document make(Tin t, Generation next_generation, const std::filesystem::path& p,
                         MaterialTable table = MaterialTable::presets(),
                         std::string metadata = "{}") {
        Document d;
        d.materials = std::move(table);
        d.metadata_json = std::move(metadata);
        d.tin = std::make_unique<Tin>(std::move(t));
        d.context = std::make_unique<SculptContext>(d.tin->domain());
        d.context->set_next_generation(next_generation);
        d.physics = make_cpu_erosion(*d.tin, d.materials);
        d.history = std::make_unique<History>(*d.tin);
        d.path = p;
        return d;
    }
    /// Drops the parts that refer to the TIN before the TIN.
    void close() {
        history.reset();
        physics.reset();
        context.reset();
        tin.reset();
    }
    Session session() const {
        Session s;
        s.terrain = tin->snapshot();
        s.next_generation = context->peek_generation();
        s.metadata_json = session_metadata(materials, metadata_json);
        return s;
    }
};

/// A new sandbox: 1 m x 1 m of sand with dunes, ripples and a band of moist sand (see
/// document.cpp).
Tin default_sandbox();

}  // namespace sandtin::editor
