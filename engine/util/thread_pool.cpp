#include "util/thread_pool.hpp"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace sandtin {

namespace {

std::pair<std::size_t, std::size_t> chunk(std::size_t n, int parts, int index) {
    const std::size_t p = static_cast<std::size_t>(parts);
    const std::size_t i = static_cast<std::size_t>(index);
    return {n * i / p, n * (i + 1) / p};
}

void relax_cpu() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

/// Spins until done() or kSpinMicroseconds pass; returns done().
template <class Done>
bool spin_until(Done done) {
    const auto until =
        std::chrono::steady_clock::now() + std::chrono::microseconds(ThreadPool::kSpinMicroseconds);
    for (int i = 0;; ++i) {
        if (done()) return true;
        relax_cpu();
        if ((i & 63) == 63 && std::chrono::steady_clock::now() > until) return done();
    }
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
    const int extra = std::max(0, threads - 1);
    workers_.reserve(static_cast<std::size_t>(extra));
    for (int i = 0; i < extra; ++i)
        workers_.emplace_back([this, i] { worker(i + 1); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        generation_.fetch_add(1, std::memory_order_release);  // spinners look, and stop
    }
    wake_.notify_all();
    for (std::thread& t : workers_)
        t.join();
}

void ThreadPool::parallel_for(std::size_t n,
                              const std::function<void(std::size_t, std::size_t, int)>& body) {
    if (workers_.empty() || n < 2) {
        body(0, n, 0);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        job_ = &body;
        job_size_ = n;
        pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
        generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    const auto [b, e] = chunk(n, threads(), 0);
    body(b, e, 0);
    if (!spin_until([this] { return pending_.load(std::memory_order_acquire) == 0; })) {
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
    }
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = nullptr;
}

void ThreadPool::worker(int index) {
    std::size_t seen = 0;
    for (;;) {
        const std::function<void(std::size_t, std::size_t, int)>* job = nullptr;
        std::size_t n = 0;
        // The next job of a burst comes within microseconds: spin for it before sleeping.
        spin_until([&] { return generation_.load(std::memory_order_acquire) != seen; });
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(
                lock, [&] { return stop_ || generation_.load(std::memory_order_relaxed) != seen; });
            if (stop_) return;
            seen = generation_.load(std::memory_order_relaxed);
            job = job_;
            n = job_size_;
        }
        const auto [b, e] = chunk(n, threads(), index);
        (*job)(b, e, index);
        if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // The last one: the caller may be asleep, or between its check and its sleep
            // (the lock orders this notification after that).
            { std::lock_guard<std::mutex> lock(mutex_); }
            done_.notify_one();
        }
    }
}

}  // namespace sandtin
