#include "smart/serve/upload_budget.hpp"

namespace smart::serve {

bool UploadBudget::Lease::take(std::size_t bytes) {
  if (!budget_.try_take(bytes)) return false;
  held_ += bytes;
  return true;
}

std::size_t UploadBudget::in_use() const {
  std::lock_guard lock(mutex_);
  return in_use_;
}

bool UploadBudget::try_take(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  if (bytes > capacity_ - in_use_) return false;
  in_use_ += bytes;
  return true;
}

void UploadBudget::give_back(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  in_use_ -= bytes;
}

}  // namespace smart::serve
