// Internal to sim/: a fixed pool of threads that runs body(k) for k = 0..n-1 in parallel, k = 0 on
// the calling thread, with barriers at start and end (the sub-step barriers of World::step). An
// exception in any body is rethrown on the calling thread.
#pragma once

#include <atomic>
#include <barrier>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace smart::sim::detail {

class Workers {
 public:
  explicit Workers(int n) : n_(std::max(1, n)), start_(n_), done_(n_) {
    for (int k = 1; k < n_; ++k) {
      threads_.emplace_back([this, k] {
        for (;;) {
          start_.arrive_and_wait();
          if (stop_.load()) return;
          run_one(k);
          done_.arrive_and_wait();
        }
      });
    }
  }
  ~Workers() {
    stop_.store(true);
    if (n_ > 1) start_.arrive_and_wait();
    for (auto& t : threads_) t.join();
  }
  int size() const { return n_; }
  void run(const std::function<void(int)>& body) {
    body_ = &body;
    error_ = nullptr;
    if (n_ > 1) start_.arrive_and_wait();
    run_one(0);
    if (n_ > 1) done_.arrive_and_wait();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run_one(int k) {
    try {
      (*body_)(k);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
  int n_;
  std::barrier<> start_, done_;
  std::vector<std::thread> threads_;
  std::atomic<bool> stop_{false};
  const std::function<void(int)>* body_ = nullptr;
  std::exception_ptr error_;
  std::mutex mutex_;
};

}  // namespace smart::sim::detail
