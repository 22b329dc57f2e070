// The thread pool (util/thread_pool.hpp): every index of a job once, in the chunks its
// contract names, through bursts of jobs that reach spinning workers, jobs after the workers
// have gone to sleep, ranges smaller than the thread count, and destruction while workers spin
// or sleep. A lost wake-up would hang a test (ctest's timeout fails it); a race shows under
// ThreadSanitizer, which runs these (test.sh).

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

#include "util/thread_pool.hpp"

namespace sandtin {
namespace {

TEST(ThreadPool, ABurstOfJobsCoversEveryIndexOnceEachTime) {
    ThreadPool pool(2);
    const std::size_t n = 1000;
    std::vector<int> hits(n, 0);
    for (int job = 0; job < 20000; ++job) {
        pool.parallel_for(n, [&](std::size_t begin, std::size_t end, int) {
            for (std::size_t i = begin; i < end; ++i)
                ++hits[i];
        });
    }
    for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(hits[i], 20000) << i;
}

TEST(ThreadPool, ChunksAreContiguousEqualAndNamedByThread) {
    for (const int threads : {1, 2, 3}) {
        ThreadPool pool(threads);
        EXPECT_EQ(pool.threads(), threads);
        for (const std::size_t n : {0u, 1u, 2u, 3u, 10u, 1001u}) {
            std::vector<std::size_t> begins(static_cast<std::size_t>(threads), n + 1);
            std::vector<std::size_t> ends(static_cast<std::size_t>(threads), n + 1);
            pool.parallel_for(n, [&](std::size_t begin, std::size_t end, int thread) {
                begins[static_cast<std::size_t>(thread)] = begin;
                ends[static_cast<std::size_t>(thread)] = end;
            });
            if (n < 2 || threads == 1) {
                // Run on the caller alone, whole.
                EXPECT_EQ(begins[0], 0u);
                EXPECT_EQ(ends[0], n);
                continue;
            }
            // Thread t takes [n t / T, n (t + 1) / T): together [0, n), in order.
            for (int t = 0; t < threads; ++t) {
                const std::size_t k = static_cast<std::size_t>(t);
                EXPECT_EQ(begins[k], n * k / static_cast<std::size_t>(threads)) << n;
                EXPECT_EQ(ends[k], n * (k + 1) / static_cast<std::size_t>(threads)) << n;
            }
        }
    }
}

TEST(ThreadPool, AJobAfterTheWorkersFellAsleepStillRuns) {
    ThreadPool pool(2);
    std::atomic<int> ran{0};
    for (int round = 0; round < 5; ++round) {
        // Well past the spin: the worker sleeps on the condition variable.
        std::this_thread::sleep_for(std::chrono::microseconds(20 * ThreadPool::kSpinMicroseconds));
        pool.parallel_for(2, [&](std::size_t begin, std::size_t end, int) {
            ran += static_cast<int>(end - begin);
        });
        EXPECT_EQ(ran.load(), 2 * (round + 1));
    }
}

TEST(ThreadPool, IsDestroyedWhileItsWorkersSpinOrSleepWithEveryJobDone) {
    // Each pool runs one job and is destroyed at once, its workers still spinning for the
    // next; the last one after its workers fell asleep. Every job's indices were all run
    // before parallel_for returned, and destruction returns (a hang fails on ctest's timeout).
    std::atomic<int> ran{0};
    for (int k = 0; k < 200; ++k) {
        ThreadPool spinning(2);
        spinning.parallel_for(10, [&](std::size_t begin, std::size_t end, int) {
            ran += static_cast<int>(end - begin);
        });
        EXPECT_EQ(ran.load(), 10 * (k + 1));
    }
    {
        ThreadPool sleeping(3);
        sleeping.parallel_for(10, [&](std::size_t begin, std::size_t end, int) {
            ran += static_cast<int>(end - begin);
        });
        std::this_thread::sleep_for(std::chrono::microseconds(20 * ThreadPool::kSpinMicroseconds));
    }
    EXPECT_EQ(ran.load(), 2010);
}

}  // namespace
}  // namespace sandtin
