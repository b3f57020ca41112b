#include "p4/track/camera_pool.h"

namespace p4::track {

CameraPool::CameraPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { Work(); });
}

CameraPool::~CameraPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

bool CameraPool::TakeAndRun() {
  std::unique_lock lock(mutex_);
  if (!task_ || next_ >= count_) return false;
  const int i = next_++;
  ++running_;
  const auto* task = task_;
  lock.unlock();
  (*task)(i);
  lock.lock();
  --running_;
  if (next_ >= count_ && running_ == 0) done_.notify_all();
  return true;
}

void CameraPool::Work() {
  long seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    while (TakeAndRun()) {
    }
  }
}

void CameraPool::Run(int n, const std::function<void(int)>& task) {
  {
    std::lock_guard lock(mutex_);
    task_ = &task;
    next_ = 0;
    count_ = n;
    ++generation_;
  }
  wake_.notify_all();
  while (TakeAndRun()) {
  }
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return next_ >= count_ && running_ == 0; });
  task_ = nullptr;
}

}  // namespace p4::track
