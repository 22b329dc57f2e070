#include "haptics/live_editor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "haptics/snapshot_builder.hpp"
#include "physics/sand_physics.hpp"
#include "tools/stamp.hpp"

namespace sandtin::haptics {

LiveEditor::LiveEditor(Tin& tin, std::shared_ptr<const Tool> tool, SculptContext& context,
                       LiveEditSettings settings, MaterialTable materials)
    : tin_(tin),
      tool_(std::move(tool)),
      context_(context),
      settings_(settings),
      materials_(std::move(materials)) {
    if (!tool_) throw std::invalid_argument("live editor: no tool");
    if (!(settings_.spacing > 0.0) || !std::isfinite(settings_.spacing))
        throw std::invalid_argument("live editor: spacing must be a positive length");
    if (settings_.erode_iterations < 0)
        throw std::invalid_argument("live editor: erode_iterations must be >= 0");
    if (settings_.erode_iterations > 0) {
        TalusSettings talus;
        talus.parameters = settings_.physics;
        physics_ = std::make_unique<SandPhysics>(tin_, materials_, talus);
    }
    placement_.centre = tin_.domain().centre();
}

LiveEditor::~LiveEditor() = default;

bool LiveEditor::touches_sand(const ToolPlacement& at) {
    // The tool's lowest point against the terrain under its centre and its inner contour.
    const Rect d = tin_.domain();
    const auto below = [&](Vec2 p) {
        const Vec2 q{std::clamp(p.x, d.min.x, d.max.x), std::clamp(p.y, d.min.y, d.max.y)};
        const std::optional<double> h = tin_.height_at(q, &probe_hint_);
        return h && *h > at.bottom;
    };
    if (below(at.centre)) return true;
    const ToolFrame frame(*tool_, at);
    for (const Vec2& local : tool_->shape().inner) {
        if (below(frame.to_world(local))) return true;
    }
    return false;
}

void LiveEditor::stamp_samples(const std::vector<StrokeSample>& samples, double bottom,
                               EditResult& result) {
    for (const StrokeSample& s : samples) {
        // A click without motion keeps the tool's last heading.
        const double heading =
            s.direction ? std::atan2(s.direction->y, s.direction->x) : placement_.angle;
        const ToolPlacement at{s.position, heading, bottom};
        placement_.angle = at.angle;
        if (!touches_sand(at)) {
            ++result.skipped;
            continue;
        }
        const StampReport r = stamp(tin_, *tool_, at, context_, s.direction);
        ++result.stamps;
        ++total_stamps_;
        result.volume_change += r.volume_change;
        if (physics_) {
            eroded_.clear();
            const PhysicsStepReport p = physics_->step(settings_.erode_iterations, &eroded_);
            result.erosion_iterations += p.iterations;
            context_.simplifier.enqueue(eroded_);
            if (context_.settings.simplify_after_edit)
                context_.simplifier.run(tin_, context_.settings.simplify);
        }
    }
}

EditResult LiveEditor::apply(const EditInput& input) {
    EditResult result;
    const Rect d = tin_.domain();
    if (!std::isfinite(input.position.x) || !std::isfinite(input.position.y) ||
        !std::isfinite(input.position.z)) {
        return result;  // a device glitch: ignore the sample
    }
    // Strokes stay on the terrain; the tool itself is where the device is, so that off the
    // terrain its snapshot has nothing to touch (force_model.hpp, rule 5).
    const Vec2 xy{std::clamp(input.position.x, d.min.x, d.max.x),
                  std::clamp(input.position.y, d.min.y, d.max.y)};
    placement_.centre = {input.position.x, input.position.y};
    placement_.bottom = input.position.z;
    const bool pressed = (input.buttons & settings_.button_mask) != 0;
    if (pressed) {
        if (!sampler_) sampler_.emplace(settings_.spacing);
        stamp_samples(sampler_->add_point(xy), input.position.z, result);
    } else if (sampler_) {
        stamp_samples(sampler_->finish(), input.position.z, result);
        sampler_.reset();
    }
    return result;
}

HapticSnapshot LiveEditor::snapshot() {
    return build_snapshot(tin_, *tool_, placement_, materials_, &snapshot_hint_);
}

}  // namespace sandtin::haptics
