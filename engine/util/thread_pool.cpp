#include "util/thread_pool.hpp"

#include <algorithm>

namespace sandtin {

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
    }
    wake_.notify_all();
    for (std::thread& t : workers_)
        t.join();
}

namespace {

std::pair<std::size_t, std::size_t> chunk(std::size_t n, int parts, int index) {
    const std::size_t p = static_cast<std::size_t>(parts);
    const std::size_t i = static_cast<std::size_t>(index);
    return {n * i / p, n * (i + 1) / p};
}

}  // namespace

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
        pending_ = static_cast<int>(workers_.size());
        ++generation_;
    }
    wake_.notify_all();
    const auto [b, e] = chunk(n, threads(), 0);
    body(b, e, 0);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_ == 0; });
    job_ = nullptr;
}

void ThreadPool::worker(int index) {
    std::size_t seen = 0;
    for (;;) {
        const std::function<void(std::size_t, std::size_t, int)>* job = nullptr;
        std::size_t n = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            job = job_;
            n = job_size_;
        }
        const auto [b, e] = chunk(n, threads(), index);
        (*job)(b, e, index);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            --pending_;
        }
        done_.notify_one();
    }
}

}  // namespace sandtin
