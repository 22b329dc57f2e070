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

/// The terrain being edited and everything that follows its lifetime.
struct Document {
    std::filesystem::path path;
    std::unique_ptr<Tin> tin;
    std::unique_ptr<SculptContext> context;
    std::unique_ptr<Erosion> physics;  ///< CPU here; the app may switch it to the GPU
    std::unique_ptr<History> history;
    MaterialTable materials = MaterialTable::presets();
    /// The metadata the terrain came with (an import record, another tool's keys); saves keep
    /// it, with the materials replaced.
    std::string metadata_json = "{}";
    bool dirty = false;

    /// A new terrain with its material table (presets for a new or imported terrain) and the
    /// metadata it came with.
    void adopt(Tin t, Generation next_generation, const std::filesystem::path& p,
               MaterialTable table = MaterialTable::presets(), std::string metadata = "{}") {
        history.reset();
        materials = std::move(table);
        metadata_json = std::move(metadata);
        physics.reset();
        tin = std::make_unique<Tin>(std::move(t));
        context = std::make_unique<SculptContext>(tin->domain());
        context->set_next_generation(next_generation);
        physics = make_cpu_erosion(*tin, materials);
        history = std::make_unique<History>(*tin);
        path = p;
        dirty = false;
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
