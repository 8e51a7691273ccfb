// Contract: the memory all uploads being read at once may hold (issue 25: 8 concurrent 60 MB
// uploads took 1.4 GB). Each upload leases from one budget as its bytes arrive; a take() that
// would pass the budget fails (the server answers 503 and the client retries later), and a
// lease gives back what it took when it ends. Thread-safe; pure (no I/O).
#pragma once

#include <cstddef>
#include <mutex>

namespace smart::serve {

class UploadBudget {
 public:
  explicit UploadBudget(std::size_t bytes) : capacity_(bytes) {}
  UploadBudget(const UploadBudget&) = delete;
  UploadBudget& operator=(const UploadBudget&) = delete;

  class Lease {
   public:
    explicit Lease(UploadBudget& budget) : budget_(budget) {}
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { budget_.give_back(held_); }
    // Takes `bytes` more; false (nothing taken) when the budget would be passed.
    bool take(std::size_t bytes);
    std::size_t held() const { return held_; }

   private:
    UploadBudget& budget_;
    std::size_t held_ = 0;
  };

  std::size_t capacity() const { return capacity_; }
  std::size_t in_use() const;

 private:
  bool try_take(std::size_t bytes);
  void give_back(std::size_t bytes);

  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::size_t in_use_ = 0;
};

}  // namespace smart::serve
