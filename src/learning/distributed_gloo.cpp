// The only file that touches torch's c10d (an internal API): Communicator over a Gloo process
// group with a TCP (or file) store for the rendezvous.
#include <torch/torch.h>
#include <torch/csrc/distributed/c10d/FileStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <chrono>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/learning/distributed.h"

namespace sims::learning {

namespace {

bool IsLoopback(const std::string& addr) {
  return addr == "localhost" || addr.rfind("127.", 0) == 0 || addr == "::1";
}

class GlooCommunicator : public Communicator {
 public:
  explicit GlooCommunicator(const DistributedConfig& c) : config_(c) {
    const auto timeout = std::chrono::milliseconds(static_cast<int64_t>(c.timeout_seconds * 1e3));
    Guard("joining the process group at " + Where(), [&] {
      c10::intrusive_ptr<c10d::Store> store;
      if (!c.store_file.empty()) {
        store = c10::make_intrusive<c10d::FileStore>(c.store_file, c.world_size);
      } else {
        c10d::TCPStoreOptions o;
        o.port = static_cast<std::uint16_t>(c.master_port);
        o.isServer = c.rank == 0;
        o.numWorkers = c.world_size;
        o.waitWorkers = false;
        o.timeout = timeout;
        store = c10::make_intrusive<c10d::TCPStore>(c.master_addr, o);
      }
      store->setTimeout(timeout);
      auto options = c10d::ProcessGroupGloo::Options::create(timeout);
      // Loopback runs (one machine) bind to 127.0.0.1; otherwise the host's own address.
      options->devices.push_back(IsLoopback(c.master_addr)
                                     ? c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1")
                                     : c10d::ProcessGroupGloo::createDefaultDevice());
      options->threads = 1;
      group_ = c10::make_intrusive<c10d::ProcessGroupGloo>(store, c.rank, c.world_size, options);
    });
  }

  int rank() const override { return config_.rank; }
  int world_size() const override { return config_.world_size; }

  void AllReduceSum(float* data, int64_t n) override {
    Reduce(torch::from_blob(data, {n}, torch::kFloat32), n * 4);
  }
  void AllReduceSum(double* data, int64_t n) override {
    Reduce(torch::from_blob(data, {n}, torch::kFloat64), n * 8);
  }
  void StartAllReduceSum(float* data, int64_t n) override {
    Guard("all-reduce", [&] {
      std::vector<at::Tensor> ts{torch::from_blob(data, {n}, torch::kFloat32)};
      pending_.push_back(group_->allreduce(ts));
    });
    Count(n * 4);
  }
  void WaitAll() override {
    Guard("all-reduce", [&] {
      for (auto& w : pending_) w->wait();
      pending_.clear();
    });
  }
  void Broadcast(float* data, int64_t n, int root) override {
    Cast(torch::from_blob(data, {n}, torch::kFloat32), root);
  }
  void Broadcast(double* data, int64_t n, int root) override {
    Cast(torch::from_blob(data, {n}, torch::kFloat64), root);
  }
  void Broadcast(std::string* bytes, int root) override {
    double size = static_cast<double>(bytes->size());
    Broadcast(&size, 1, root);
    bytes->resize(static_cast<size_t>(size));
    if (!bytes->empty())
      Cast(torch::from_blob(bytes->data(), {static_cast<int64_t>(bytes->size())}, torch::kUInt8),
           root);
  }
  int64_t bytes_reduced() const override { return bytes_; }
  int64_t reduce_calls() const override { return calls_; }
  int64_t max_reduce_bytes() const override { return max_bytes_; }
  double collective_seconds() const override { return seconds_; }

 private:
  std::string Where() const {
    return config_.store_file.empty()
               ? config_.master_addr + ":" + std::to_string(config_.master_port)
               : config_.store_file;
  }

  // Gloo reports a dead or silent peer as c10::Error; the run ends with one project error.
  template <class F>
  void Guard(const std::string& what, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      f();
      seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      std::string msg = e.what();
      if (const auto nl = msg.find('\n'); nl != std::string::npos) msg.resize(nl);
      throw Error("distributed training, rank " + std::to_string(config_.rank) + " of " +
                  std::to_string(config_.world_size) + ": " + what +
                  " failed (a peer exited or did not answer within " +
                  std::to_string(static_cast<int>(config_.timeout_seconds)) + " s): " + msg);
    }
  }

  void Reduce(torch::Tensor t, int64_t bytes) {
    Guard("all-reduce", [&] {
      std::vector<at::Tensor> ts{t};
      group_->allreduce(ts)->wait();
    });
    Count(bytes);
  }

  void Count(int64_t bytes) {
    bytes_ += bytes;
    max_bytes_ = std::max(max_bytes_, bytes);
    ++calls_;
  }

  void Cast(torch::Tensor t, int root) {
    Guard("broadcast", [&] {
      std::vector<at::Tensor> ts{t};
      c10d::BroadcastOptions o;
      o.rootRank = root;
      group_->broadcast(ts, o)->wait();
    });
  }

  DistributedConfig config_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
  std::vector<c10::intrusive_ptr<c10d::Work>> pending_;
  int64_t bytes_ = 0, calls_ = 0, max_bytes_ = 0;
  double seconds_ = 0;
};

}  // namespace

std::unique_ptr<Communicator> ConnectProcessGroup(const DistributedConfig& config) {
  if (config.world_size < 2 || config.rank < 0 || config.rank >= config.world_size)
    ThrowInputError(config.source.empty() ? "distributed config" : config.source, "rank",
                    "0 <= rank < world_size with world_size >= 2",
                    std::to_string(config.rank) + " of " + std::to_string(config.world_size));
  auto c = std::make_unique<GlooCommunicator>(config);
  spdlog::info("distributed: rank {} of {} joined ({})", config.rank, config.world_size,
               config.store_file.empty()
                   ? config.master_addr + ":" + std::to_string(config.master_port)
                   : config.store_file);
  return c;
}

}  // namespace sims::learning
