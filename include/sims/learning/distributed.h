// Data-parallel training: where a process sits in a run, and the few collectives the learner
// needs. The process group behind Communicator is torch's c10d over Gloo, kept in one source
// file (src/learning/distributed_gloo.cpp) because c10d is an internal torch API; nothing here
// includes torch.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace sims::learning {

/// A TCP port on 127.0.0.1 that was free a moment ago (the kernel picks it): a rendezvous
/// port for ranks started on this machine.
int FreeLoopbackPort();

/// Rank, world size and rendezvous of one data-parallel process.
struct DistributedConfig {
  int rank = 0;                           ///< This process, 0 ≤ rank < world_size.
  int world_size = 1;                     ///< Number of processes.
  std::string master_addr = "127.0.0.1";  ///< Host of rank 0's TCP store.
  int master_port = 29500;                ///< Port of rank 0's TCP store.
  std::string store_file;        ///< Rendezvous through this shared file instead of TCP when set.
  double timeout_seconds = 120;  ///< A collective that waits longer ends the run with an error.
  int check_every = 10;          ///< Compare a parameter checksum across ranks every K iterations.
  std::string source;            ///< Where the values came from (for messages).
};

/// Reads the launcher's variables: torchrun's RANK/WORLD_SIZE/MASTER_ADDR/MASTER_PORT, else
/// Open MPI's OMPI_COMM_WORLD_RANK/SIZE, else Slurm's SLURM_PROCID/SLURM_NTASKS (master from
/// SIMS_MASTER_ADDR/MASTER_ADDR or 127.0.0.1). `lookup` returns nullptr for unset names (pass
/// std::getenv). Returns nullopt when no launcher is present or the world has one process;
/// throws sims::Error naming the variable when a value is malformed.
std::optional<DistributedConfig> DistributedConfigFromEnvironment(
    const std::function<const char*(const char*)>& lookup);

/// Sum all-reduce and broadcast among the ranks of one run. Every rank must make the same
/// calls in the same order with the same sizes; a failed or timed-out peer throws sims::Error.
class Communicator {
 public:
  virtual ~Communicator() = default;
  /// This process's rank.
  virtual int rank() const = 0;
  /// Number of ranks.
  virtual int world_size() const = 0;
  /// In-place element-wise sum over all ranks.
  virtual void AllReduceSum(float* data, int64_t n) = 0;
  /// In-place element-wise sum over all ranks (statistics in double precision).
  virtual void AllReduceSum(double* data, int64_t n) = 0;
  /// Starts an in-place sum all-reduce and returns at once, so computation can overlap it;
  /// `data` must stay valid and untouched until WaitAll().
  virtual void StartAllReduceSum(float* data, int64_t n) = 0;
  /// Waits for every all-reduce StartAllReduceSum() began.
  virtual void WaitAll() = 0;
  /// Copies `root`'s buffer to every rank.
  virtual void Broadcast(float* data, int64_t n, int root) = 0;
  /// Copies `root`'s buffer to every rank.
  virtual void Broadcast(double* data, int64_t n, int root) = 0;
  /// Copies `root`'s byte string (any length) to every rank.
  virtual void Broadcast(std::string* bytes, int root) = 0;
  /// Bytes this rank has sent into all-reduces so far (for the scaling benchmark).
  virtual int64_t bytes_reduced() const = 0;
  /// Number of all-reduce calls so far.
  virtual int64_t reduce_calls() const = 0;
  /// Largest single all-reduce so far, in bytes (the flattened gradients in training).
  virtual int64_t max_reduce_bytes() const = 0;
  /// Wall time spent inside collectives so far: transfer plus waiting for slower ranks.
  virtual double collective_seconds() const = 0;
};

/// Joins the process group of `config` (rank 0 hosts the store); throws sims::Error naming
/// the address when peers do not arrive within the timeout.
std::unique_ptr<Communicator> ConnectProcessGroup(const DistributedConfig& config);

}  // namespace sims::learning
