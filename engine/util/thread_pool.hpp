#pragma once
// A fixed set of worker threads running a function over an index range in equal contiguous
// chunks. The partition depends only on the range and the thread count, so results that are
// combined per index are the same for any number of threads.
//
// Jobs often come in quick succession (a water step is four of them, a few hundred
// microseconds each): a worker that finished one spins for a moment (kSpinMicroseconds) on the
// next job before it sleeps on the condition variable, and the caller spins as briefly on the
// workers finishing, since waking a sleeping thread takes tens of microseconds on a virtual
// machine. An idle pool sleeps: it costs nothing between bursts.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sandtin {

class ThreadPool {
  public:
    /// How long a thread spins for the next step of a burst before it sleeps (µs).
    static constexpr int kSpinMicroseconds = 50;

    /// `threads` >= 1 workers in total; the calling thread is one of them.
    explicit ThreadPool(int threads = 1);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }
    /// Calls body(begin, end, thread_index) for each chunk of [0, n) and waits for all.
    void parallel_for(std::size_t n,
                      const std::function<void(std::size_t, std::size_t, int)>& body);

  private:
    void worker(int index);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t, std::size_t, int)>* job_ = nullptr;
    std::size_t job_size_ = 0;
    std::atomic<std::size_t> generation_{0};  ///< bumped (under mutex_) for each job
    std::atomic<int> pending_{0};             ///< workers still running the current job
    bool stop_ = false;
};

}  // namespace sandtin
