// Long document work off the UI thread (background_job.hpp): importing a heightmap, opening a
// scene and exporting run on a worker with their own inputs while the frames go on; the result
// replaces the document (or the status line says what was written) on the UI thread once the
// work is done. While a job runs, whatever would conflict with it waits: editing the terrain,
// another document command, a save. And the erosion settling to rest, measured for its bar
// (settle_progress.hpp).

#include "app.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "physics/project_out_of_repose.hpp"
#include "physics/settle_by_projection.hpp"
#include "physics/settle_fitted_to_kinks.hpp"
#include "recent_files.hpp"

namespace sandtin::editor {

namespace {

/// Seconds the erosion's frames count for while settling: a scripted frame 1/60 s, as a held
/// pour; a slow interactive frame at most a quarter of a second.
double settle_seconds(bool scripted, Clock::time_point& last, Clock::time_point now) {
    const double real =
        last == Clock::time_point{} ? 0.0 : std::chrono::duration<double>(now - last).count();
    last = now;
    return scripted ? kScriptFrameSeconds : std::min(real, 0.25);
}

/// A scene name for an imported heightmap: beside it, with its stem, and not taken by a file
/// or an autosave ("bay-hills.sandtin", else "bay-hills-2.sandtin", ...).
std::filesystem::path scene_name_for_import(const std::filesystem::path& heightmap) {
    const std::filesystem::path folder = heightmap.parent_path();
    const std::string stem = heightmap.stem().string();
    for (int n = 1; n < 1000; ++n) {
        const std::string name = n == 1 ? stem : stem + "-" + std::to_string(n);
        const std::filesystem::path candidate = folder / (name + ".sandtin");
        std::error_code ec;
        if (!std::filesystem::exists(candidate, ec) && !find_autosave(candidate)) return candidate;
    }
    return folder / (stem + "-imported.sandtin");
}

}  // namespace

// ---- Starting and finishing ---------------------------------------------------------------

bool App::refuse_while_busy(const std::string& what) {
    if (!busy()) return false;
    report(what + " not done: " + job_->progress().title +
           " is still running (let it finish, or Cancel it)");
    return true;
}

void App::start_job(const std::string& kind, const std::string& title, BackgroundJob::Work work,
                    std::function<void()> done) {
    sculpting_.close_level(doc_);  // a gesture under way ends here: the pointer is the job's now
    left_down_ = false;
    job_kind_ = kind;
    job_done_ = std::move(done);
    job_record_ = {{"kind", kind},    {"title", title},       {"frames", 0},
                   {"bar_frames", 0}, {"outcome", "running"}, {"fractions_shown", 0}};
    // A job may read the document on its worker (Save, Export) while the frames take the
    // journal's changes: those takes must not recycle dead ids, which the worker reads.
    if (doc_.has_terrain()) doc_.tin().hold_id_recycling(true);
    job_ = std::make_unique<BackgroundJob>(title, std::move(work), job_pause_at_);
    job_popup_open_ = true;
}

void App::start_document_job(const std::string& kind, const std::string& title, ReadDocument read,
                             std::function<void(PreparedDocument)> install) {
    auto next = std::make_shared<std::optional<PreparedDocument>>();
    gpu::VulkanContext& gpu = window_->context();
    start_job(
        kind, title,
        [next, read = std::move(read), &gpu](const ProgressCallback& progress) {
            // The document, then its view built and uploaded here too (TerrainView::prepare):
            // 58 % of the time on a 10^6-vertex scene.
            Document document = read(progress_part(progress, 0.0, 0.42));
            PreparedView view =
                TerrainView::prepare(document, gpu, progress_part(progress, 0.42, 1.0));
            next->emplace(PreparedDocument{std::move(document), std::move(view)});
        },
        [next, install = std::move(install)] { install(std::move(**next)); });
}

void App::cancel_job() {
    if (!job_) return;
    keys_after_job_.clear();  // what was typed to follow the work goes with it
    job_->cancel();
    report("cancelling: " + job_->progress().title);
}

void App::poll_job() {
    if (!job_) return;
    const JobOutcome outcome = job_->outcome();
    if (outcome == JobOutcome::Running) {
        job_record_["frames"] = job_record_["frames"].get<int>() + 1;
        return;
    }
    const JobProgress last = job_->progress();
    const std::string error = job_->error();
    // A scene or heightmap read to the end after Cancel was pressed is dropped all the same:
    // nothing was touched yet. An export or a save whose files were written is done, and says
    // so.
    const bool read_only = job_kind_ != "export" && job_kind_ != "save";
    const bool cancelled = outcome == JobOutcome::Cancelled || (read_only && last.cancel_requested);
    std::function<void()> done = std::move(job_done_);
    job_done_ = nullptr;
    job_.reset();
    if (doc_.has_terrain()) doc_.tin().hold_id_recycling(false);  // the worker is done with it
    job_record_["outcome"] = cancelled ? "cancelled" : to_string(outcome);
    job_record_["seconds"] = last.elapsed_seconds;
    const bool startup = std::exchange(startup_open_, false);
    const bool must_succeed = std::exchange(script_job_must_succeed_, false);
    if (startup)
        startup_job_record_ = job_record_;
    else if (jobs_done_.size() < 100)
        jobs_done_.push_back(job_record_);
    redraw_frames_ = std::max(redraw_frames_, 2);  // the popup closes, the scene appears
    if (startup && (cancelled || outcome == JobOutcome::Failed)) {
        initial_scene_failed(cancelled ? "cancelled" : error);
    } else if (cancelled) {
        report(last.title + " cancelled: " +
               (job_kind_ == "settle" ? "the sand is as it was"
                : read_only           ? "the scene open before is as it was"
                                      : "no file was written"));
    } else if (outcome == JobOutcome::Failed) {
        if (must_succeed) throw std::runtime_error(job_kind_ + " failed: " + error);
        report(job_kind_ + " failed: " + error);
    } else {
        if (last.cancel_requested)
            report(last.title + ": Cancel came after the files were written");
        try {
            if (done) done();
        } catch (const std::exception& e) {
            report(job_kind_ + " failed: " + e.what());
        }
    }
    // The keys typed meanwhile, in order, once the work succeeded (one that starts another
    // job queues the rest again behind it); after a failure or a Cancel they are dropped.
    std::vector<std::pair<int, bool>> keys = std::move(keys_after_job_);
    keys_after_job_.clear();
    if (cancelled || outcome == JobOutcome::Failed) return;
    for (const auto& [k, ctrl] : keys)
        key(k, ctrl);
}

void App::note_job_shown(const JobProgress& shown) {
    job_record_["bar_frames"] = job_record_["bar_frames"].get<int>() + 1;
    job_record_["stage_last"] = shown.stage;
    if (shown.fraction > 0.0 && shown.fraction < 1.0) {
        job_record_["fractions_shown"] = job_record_["fractions_shown"].get<int>() + 1;
        if (!job_record_.contains("fraction_min_shown"))
            job_record_["fraction_min_shown"] = shown.fraction;
        job_record_["fraction_max_shown"] = shown.fraction;
    }
}

// ---- The jobs -----------------------------------------------------------------------------

void App::open_reporting(const std::filesystem::path& p) {
    if (refuse_while_busy("open " + p.string())) return;
    // Read before anything is dropped: a file that does not load (or a Cancel) leaves the
    // scene as it was.
    start_document_job(
        "open", "Opening " + p.filename().string(),
        [p](const ProgressCallback& progress) { return Document::open(p, progress); },
        [this, p](PreparedDocument next) {
            hand_unsaved_edits_to_autosave();
            set_scene_field(p.string());
            note_recent_file(settings_.recent_files, p);
            install_document(std::move(next), "opened " + p.string());
            offer_recovery_of(p);
        });
}

void App::recover_document(const std::filesystem::path& scene) {
    if (refuse_while_busy("recover the autosave of " + scene.string())) return;
    start_document_job(
        "recover", "Recovering " + scene.filename().string(),
        [scene](const ProgressCallback& progress) { return Document::recovered(scene, progress); },
        [this, scene](PreparedDocument next) {
            install_document(std::move(next), "recovered the autosave of " + scene.string());
        });
}

void App::import_document(const std::filesystem::path& heightmap) {
    if (refuse_while_busy("import " + heightmap.string())) return;
    start_document_job(
        "import", "Importing " + heightmap.filename().string(),
        [heightmap](const ProgressCallback& progress) {
            return Document::imported(heightmap, progress);
        },
        [this, heightmap](PreparedDocument next) { finish_import(heightmap, std::move(next)); });
}

void App::finish_import(const std::filesystem::path& heightmap, PreparedDocument next) {
    hand_unsaved_edits_to_autosave();
    // An imported model is a scene of its own, with a name of its own in the Scene field,
    // so Save never writes it over the scene it replaced.
    const std::filesystem::path name = scene_name_for_import(heightmap);
    set_scene_field(name.string());
    set_import_field(heightmap.string());
    note_recent_file(settings_.recent_files, heightmap);
    install_document(std::move(next), "imported " + heightmap.string() +
                                          " (untitled: Save writes " + name.string() + ")");
}

void App::save(const std::filesystem::path& p, std::function<void()> then) {
    if (refuse_while_busy("save to " + p.string())) return;
    sculpting_.close_level(doc_);
    if (const std::optional<std::string> problem = Document::save_name_problem(p)) {
        report("save failed: " + *problem);
        return;
    }
    // An autosave still being written would otherwise land after the save retired it.
    autosave_writer_.cancel();
    // The scene as it is at this click: nothing edits the document while the job runs (the
    // tools, the erosion and the document commands wait for it), and the UI thread only reads
    // the terrain meanwhile (frames draw it; the readers of its journal take their changes,
    // recycling no ids while the job holds it, start_job). So the copy is the worker's too: it
    // was 0.12-0.45 s of a 10^6-vertex save's frame on the UI thread.
    const Document* doc = &doc_;
    start_job(
        "save", "Saving " + p.filename().string(),
        [doc, p](const ProgressCallback& progress) {
            if (progress) progress({0.0, "copying the scene"});
            const Session session = doc->session();
            if (progress) progress({0.2, "writing the scene"});  // the last point to Cancel
            save_session_clearing_autosave(p, session);
        },
        [this, p, then = std::move(then)] {
            doc_.saved_as(p);
            set_scene_field(p.string());
            note_recent_file(settings_.recent_files, p);
            report("saved " + p.string());
            if (then) then();
        });
}

void App::export_reporting(const std::filesystem::path& p) {
    if (refuse_while_busy("export to " + p.string())) return;
    try {
        sculpting_.close_level(doc_);
        // The scene as it is at this click, exported by the worker straight from the
        // document: nothing edits it while the job runs (see save above). A copy and a
        // rebuild from it took a 10^6-vertex export 0.2 s of a frame and 1.2 s of the job.
        // The format is checked here, so that a wrong name fails at once.
        static_cast<void>(export_format_for(p));
        const Document* doc = &doc_;
        auto written = std::make_shared<std::size_t>(0);
        start_job(
            "export", "Exporting " + p.filename().string(),
            [doc, p, written](const ProgressCallback& progress) {
                *written = doc->export_to(p, progress).files.size();
            },
            [this, written] { report("exported " + std::to_string(*written) + " file(s)"); });
    } catch (const std::exception& e) {
        report(std::string("export failed: ") + e.what());
    }
}

// ---- Erosion to rest ----------------------------------------------------------------------

void App::update_settle(const ErosionFrame& e) {
    // Only the erosion's own settle (after Run, with no gesture before it) is long work; a
    // stroke's settling belongs to the stroke and shows no bar.
    const bool own_settle =
        e.ran && !left_down_ && e.active > 0 && sculpting_.open_level() == Document::kErosionLevel;
    if (!own_settle) {
        settle_.end();
        last_settle_at_ = {};
        return;
    }
    const bool was_shown = settle_.shown();
    settle_.step(e.active, settle_seconds(options_.scripted(), last_settle_at_, Clock::now()));
    if (settle_.shown()) {
        settle_record_["bar_frames"] = settle_record_.value("bar_frames", 0) + 1;
        settle_record_["fraction_max_shown"] = settle_.progress().fraction;
        if (!was_shown) settle_record_["shown"] = true;
    }
}

void App::settle_exactly() {
    if (refuse_while_busy("settle exactly")) return;
    sculpting_.close_level(doc_);  // what slid before is its own level
    start_settle_projection(settings_.settle_fit_bends ? 1 : 0, 0);
}

void App::start_settle_projection(int fit_rounds, std::size_t fitted) {
    // The worker reads the terrain and projects it: nothing edits the terrain while the job
    // runs (the erosion and the tools wait for it, and the frames' takes recycle no ids,
    // start_job), so the copy is the worker's too (it was 0.4 s of a 10^6-vertex frame).
    // apply_projection refuses heights from another terrain.
    auto input = std::make_shared<ProjectionInput>();
    auto result = std::make_shared<ReposeProjection>();
    auto region = std::make_shared<OutOfReposeReport>();
    const Tin* tin = &doc_.tin();
    auto materials = std::make_shared<const MaterialTable>(doc_.materials());
    // Fitting wants the bends converged: the projection's smaller penalty for every round.
    const bool fitting = fit_rounds > 0 || fitted > 0;
    const OutOfReposeOptions region_options =
        fitting ? kink_fitting_region_options() : OutOfReposeOptions{};
    start_job(
        "settle",
        fitted > 0 ? "Settling the sand exactly on its bends" : "Settling the sand exactly",
        [input, result, region, tin, materials, region_options](const ProgressCallback& progress) {
            if (progress) progress({0.0, "reading the terrain"});
            *input = gather_projection_input(*tin, *materials);
            ReposeProjectionOptions options;
            if (progress) {
                options.on_progress = [&progress](double fraction) {
                    progress({fraction, "projecting onto the angle of repose"});
                };
            }
            // Where the sand is out of repose: a pour on a large terrain settles at the
            // cost of its neighbourhood (project_out_of_repose.hpp).
            *result = project_out_of_repose(*input, options, region_options, region.get());
        },
        [this, input, result, region, fit_rounds, fitted] {
            if (region->rounds == 0 && fitted == 0) {
                report("settle exactly: nothing is steeper than its angle of repose");
                return;
            }
            const std::size_t added =
                fit_rounds > 0 ? fit_projection_bends(doc_.tin(), *input, *result) : 0;
            if (added > 0) {  // the next projection settles the same sand over them
                start_settle_projection(fit_rounds - 1, fitted + added);
                return;
            }
            const ProjectionSettleReport r = apply_projection(doc_.tin(), *input, *result);
            doc_.record_level("settle exactly");
            sculpting_.kick();  // the erosion finishes what the tolerance left, if anything
            char steepest[32];
            std::snprintf(steepest, sizeof steepest, "%.2f", 100.0 * r.steepest_ratio);
            report("settled exactly: " + std::to_string(region->steep_faces) +
                   " faces were steeper than repose; " + std::to_string(region->free_vertices) +
                   " vertices around them settled, the steepest face now at " + steepest +
                   " % of repose" +
                   (fitted > 0 ? "; " + std::to_string(fitted) + " vertices put on its bends"
                               : std::string()) +
                   (r.converged ? "" : " (stopped at the iteration limit: Run finishes it)"));
        });
}

void App::stop_settling() {
    if (!erosion_runs()) return;
    toggle_erosion();  // pauses: what slid so far is its level
    settle_.end();
    settle_record_["stopped"] = true;
    report("erosion stopped: what settled so far is one undo level; Run goes on");
}

}  // namespace sandtin::editor
