// A few persistent worker threads that run one task per camera and wait for all of them
// (per-camera segmentation in parallel). The calling thread works too, so `threads` = 2 uses
// one extra thread. Tasks must touch only their own camera's state.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace p4::track {

class CameraPool {
 public:
  explicit CameraPool(int threads);  // threads >= 2: the caller plus threads - 1 workers
  ~CameraPool();
  CameraPool(const CameraPool&) = delete;
  CameraPool& operator=(const CameraPool&) = delete;

  // Runs task(0) .. task(n - 1), spread over the workers and the caller; returns when all ended.
  void Run(int n, const std::function<void(int)>& task);

 private:
  void Work();
  bool TakeAndRun();  // one task of the current batch, if any is left

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;
  int next_ = 0, count_ = 0, running_ = 0;
  long generation_ = 0;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace p4::track
