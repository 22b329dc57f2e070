#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench_history.hpp"
#include "history/history.hpp"
#include "io/session_file.hpp"
#include "io/session_keeper.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::bench {

nlohmann::json bench_history(const BenchConfig& config, const ProgressCallback& progress) {
    const std::size_t points = config.quick ? 100000 : 1000000;
    const int repeats = config.quick ? 3 : 7;
    // Building the terrain and attaching the history take about as long as the rounds.
    if (progress) progress({0.0, "building the terrain and its history"});
    const Rect domain{{0.0, 0.0}, {1.0, 1.0}};
    Tin tin = Tin::random_points(domain, points, 11, [](Vec2 p) {
        return 0.05 + 0.02 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y);
    });
    tin.take_changes();
    Stopwatch attach_clock;
    History history(tin);
    const double attach_ms = attach_clock.ms();
    // The editor's autosave copy (io/session_keeper.hpp), side by side with the whole snapshot
    // the frame used to take: after each stroke and each undo.
    Stopwatch keeper_clock;
    SessionKeeper keeper(tin);
    const double keeper_ms = keeper_clock.ms();

    SculptContext context(domain);
    const Tool tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.depth = 0.01;
    // A 10 cm stroke: 11 stamps of the 4 cm circle tool.
    std::vector<Vec2> path;
    for (int i = 0; i <= 10; ++i)
        path.push_back({0.45 + 0.01 * i, 0.5 + 0.02 * std::sin(0.3 * i)});

    std::vector<double> record_ms, undo_ms, redo_ms, undo_cpu_ms, redo_cpu_ms;
    std::vector<double> follow_ms, hand_out_ms, writer_copy_ms, snapshot_ms;
    bool autosave_exact = true;
    // What the frame pays for an autosave after an edit (follow, then hand the copy out), what
    // the writer's thread pays, and the whole snapshot; the kept session must be the whole one.
    const auto autosave = [&] {
        Stopwatch f;
        keeper.follow();
        follow_ms.push_back(f.ms());
        Stopwatch h;
        const SessionSource source = keeper.hand_out(1, "{}");
        hand_out_ms.push_back(h.ms());
        Stopwatch w;
        const Session kept = source();
        writer_copy_ms.push_back(w.ms());
        Stopwatch whole_clock;
        Session whole;
        whole.terrain = tin.snapshot();
        snapshot_ms.push_back(whole_clock.ms());
        whole.next_generation = 1;
        whole.metadata_json = "{}";
        autosave_exact = autosave_exact && encode_session(kept) == encode_session(whole);
    };
    std::size_t level_bytes = 0;
    std::size_t changed = 0;
    bool exact = true;
    for (int r = 0; r < repeats; ++r) {
        if (progress) {
            const std::string stage = "stroke, undo and redo, round " + std::to_string(r + 1) +
                                      " of " + std::to_string(repeats);
            progress({0.5 + 0.5 * r / repeats, stage});
        }
        // A fresh stroke each round (a new generation), as an artist would draw it.
        if (r > 0) history.undo();
        apply_stroke(tin, tool, path, settings, context);
        Stopwatch rec;
        history.record("stroke");
        record_ms.push_back(rec.ms());
        level_bytes = history.bytes();
        autosave();
        Stopwatch u;
        CpuStopwatch uc;
        const HistoryStep undo = history.undo();
        undo_ms.push_back(u.ms());
        undo_cpu_ms.push_back(uc.ms());
        autosave();
        changed = undo.report.vertices_removed + undo.report.vertices_inserted +
                  undo.report.vertices_updated;
        Stopwatch re;
        CpuStopwatch rc;
        const HistoryStep redo = history.redo();
        redo_ms.push_back(re.ms());
        redo_cpu_ms.push_back(rc.ms());
        exact = exact && undo.report.exact() && redo.report.exact();
    }
    if (progress) progress({1.0, "done"});
    nlohmann::json out;
    out["benchmark"] = "history";
    out["vertices"] = tin.vertex_count();
    out["stroke_stamps"] = path.size();
    out["attach_ms"] = attach_ms;
    out["record_ms_median"] = median(record_ms);
    out["undo_ms_median"] = median(undo_ms);
    out["redo_ms_median"] = median(redo_ms);
    out["undo_ms_max"] = *std::max_element(undo_ms.begin(), undo_ms.end());
    // Thread CPU time: what the undo costs without the time other guests take from this VM.
    out["undo_cpu_ms_median"] = median(undo_cpu_ms);
    out["redo_cpu_ms_median"] = median(redo_cpu_ms);
    out["level_bytes"] = level_bytes;
    out["vertices_restored_per_undo"] = changed;
    out["full_vertex_copy_bytes"] = tin.vertex_count() * sizeof(VertexRecord);
    out["exact"] = exact;
    out["autosave_keeper_build_ms"] = keeper_ms;
    out["autosave_follow_ms_median"] = median(follow_ms);
    out["autosave_hand_out_ms_median"] = median(hand_out_ms);
    out["autosave_writer_copy_ms_median"] = median(writer_copy_ms);
    out["whole_snapshot_ms_median"] = median(snapshot_ms);
    out["autosave_exact"] = autosave_exact;
    out["target_undo_ms"] = 50.0;
    out["repeats"] = repeats;
    return out;
}

}  // namespace sandtin::bench
