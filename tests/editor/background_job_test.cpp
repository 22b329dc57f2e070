// Long work off the UI thread (background_job.hpp) and what its bar says (job_progress.hpp,
// settle_progress.hpp): a job ends Done with its result, Cancelled at its next check after
// Cancel (having changed nothing), or Failed with the error; its fraction never goes back; a
// job destroyed while running is cancelled and waited for. The bar's words and numbers.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "background_job.hpp"
#include "job_progress.hpp"
#include "settle_progress.hpp"

namespace sandtin::editor::background_job_test {
namespace {

/// Polls (as frames do) until the job ended; the outcome.
JobOutcome wait_for(const BackgroundJob& job) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (job.outcome() == JobOutcome::Running && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return job.outcome();
}

void wait_until_paused(const BackgroundJob& job) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!job.paused() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_TRUE(job.paused());
}

/// Ten pieces of work, each reported; the result written at the end.
BackgroundJob::Work ten_pieces(std::shared_ptr<int> result) {
    return [result](const ProgressCallback& progress) {
        int sum = 0;
        for (int i = 0; i < 10; ++i) {
            progress({i / 10.0, "piece " + std::to_string(i)});
            sum += i;
        }
        progress({1.0, "done"});
        *result = sum;
    };
}

TEST(BackgroundJob, ADoneJobHasItsResultAndEndsAtOne) {
    auto result = std::make_shared<int>(-1);
    BackgroundJob job("Adding", ten_pieces(result));
    EXPECT_EQ(wait_for(job), JobOutcome::Done);
    EXPECT_EQ(*result, 45);
    const JobProgress p = job.progress();
    EXPECT_EQ(p.title, "Adding");
    EXPECT_EQ(p.fraction, 1.0);
    EXPECT_EQ(p.stage, "done");
    EXPECT_FALSE(p.cancel_requested);
}

TEST(BackgroundJob, ACancelStopsTheWorkAtItsNextCheckAndLeavesNoResult) {
    auto result = std::make_shared<int>(-1);
    BackgroundJob job("Adding", ten_pieces(result), 0.35);
    wait_until_paused(job);
    const JobProgress mid = job.progress();
    EXPECT_GT(mid.fraction, 0.0);
    EXPECT_LT(mid.fraction, 1.0);
    EXPECT_EQ(mid.stage, "piece 4");
    job.cancel();
    EXPECT_EQ(wait_for(job), JobOutcome::Cancelled);
    EXPECT_EQ(*result, -1) << "a cancelled job hands over nothing";
    EXPECT_TRUE(job.progress().cancel_requested);
    EXPECT_LT(job.progress().fraction, 1.0);
}

TEST(BackgroundJob, AResumedJobRunsToTheEnd) {
    auto result = std::make_shared<int>(-1);
    BackgroundJob job("Adding", ten_pieces(result), 0.5);
    wait_until_paused(job);
    job.resume();
    EXPECT_EQ(wait_for(job), JobOutcome::Done);
    EXPECT_EQ(*result, 45);
}

TEST(BackgroundJob, AFailureIsReportedWithItsError) {
    BackgroundJob job("Reading", [](const ProgressCallback& progress) {
        progress({0.1, "reading"});
        throw std::runtime_error("'x.png': not a heightmap");
    });
    EXPECT_EQ(wait_for(job), JobOutcome::Failed);
    EXPECT_EQ(job.error(), "'x.png': not a heightmap");
}

TEST(BackgroundJob, TheFractionShownNeverGoesBack) {
    BackgroundJob job("Wobbling", [](const ProgressCallback& progress) {
        progress({0.6, "a"});
        progress({0.4, "b"});  // a careless report
    });
    EXPECT_EQ(wait_for(job), JobOutcome::Done);
    EXPECT_EQ(job.progress().fraction, 0.6);
}

TEST(BackgroundJob, DestroyedWhileRunningItIsCancelledAndWaitedFor) {
    auto reports = std::make_shared<std::atomic<int>>(0);
    {
        BackgroundJob job("Forever", [reports](const ProgressCallback& progress) {
            for (;;) {
                progress({0.5, "spinning"});
                ++*reports;
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
        });
        while (*reports == 0)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    const int after = *reports;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(*reports, after) << "the worker stopped with the job";
}

TEST(JobProgressText, TheEstimateWaitsForARateAndFollowsIt) {
    EXPECT_FALSE(estimate_remaining_seconds(0.0, 10.0));
    EXPECT_FALSE(estimate_remaining_seconds(0.01, 10.0)) << "under 2 %";
    EXPECT_FALSE(estimate_remaining_seconds(0.5, 0.5)) << "under a second";
    EXPECT_FALSE(estimate_remaining_seconds(1.0, 10.0)) << "done";
    EXPECT_DOUBLE_EQ(*estimate_remaining_seconds(0.25, 10.0), 30.0);
    EXPECT_DOUBLE_EQ(*estimate_remaining_seconds(0.5, 4.0), 4.0);
}

TEST(JobProgressText, DurationsPercentsAndTheTimesLine) {
    EXPECT_EQ(duration_text(0.4), "0 s");
    EXPECT_EQ(duration_text(8.0), "8 s");
    EXPECT_EQ(duration_text(125.0), "2 min 05 s");
    EXPECT_EQ(duration_text(3780.0), "1 h 03 min");
    EXPECT_EQ(percent_text(0.0), "0 %");
    EXPECT_EQ(percent_text(0.999), "99 %") << "100 % means done";
    EXPECT_EQ(percent_text(1.0), "100 %");
    JobProgress p;
    p.fraction = 0.25;
    p.elapsed_seconds = 10.0;
    EXPECT_EQ(job_times_text(p), "10 s elapsed, about 30 s left");
    p.elapsed_seconds = 0.4;
    EXPECT_EQ(job_times_text(p), "0 s elapsed, time left not known yet");
}

TEST(SettleProgress, CountsVerticesComeToRestAndNeverGoesBack) {
    SettleProgress s;
    EXPECT_FALSE(s.shown());
    s.step(1000, 0.1);
    EXPECT_EQ(s.progress().fraction, 0.0);
    EXPECT_FALSE(s.shown()) << "a short settle shows no bar";
    s.step(600, 0.3);
    EXPECT_DOUBLE_EQ(s.progress().fraction, 0.4);
    s.step(800, 0.2);  // sliding sand set more sliding: the bar holds still
    EXPECT_DOUBLE_EQ(s.progress().fraction, 0.4);
    EXPECT_TRUE(s.shown()) << SettleProgress::kShowAfterSeconds << " s passed";
    EXPECT_EQ(s.progress().stage, "800 of 1000 vertices still sliding");
    s.step(100, 0.1);
    EXPECT_DOUBLE_EQ(s.progress().fraction, 0.9);
    s.end();
    EXPECT_FALSE(s.shown());
    s.step(50, 0.1);  // a new settle starts from nothing
    EXPECT_EQ(s.progress().fraction, 0.0);
    EXPECT_DOUBLE_EQ(s.progress().elapsed_seconds, 0.1);
}

}  // namespace
}  // namespace sandtin::editor::background_job_test
