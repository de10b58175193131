#include "sims/learning/distributed.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include "sims/core/error.h"

namespace sims::learning {

int FreeLoopbackPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  SIMS_CHECK_MSG(fd >= 0, "socket() failed");
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof(addr);
  const bool ok = bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
                  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0;
  close(fd);
  SIMS_CHECK_MSG(ok, "could not find a free loopback port");
  return ntohs(addr.sin_port);
}

namespace {

// A non-negative integer variable; throws naming it when the text is not one.
int ParseCount(const char* name, const char* text, const std::string& source) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < 0 || v > (1 << 24))
    ThrowInputError(source, name, "a non-negative integer", std::string("'") + text + "'");
  return static_cast<int>(v);
}

}  // namespace

std::optional<DistributedConfig> DistributedConfigFromEnvironment(
    const std::function<const char*(const char*)>& lookup) {
  // Launchers in order of precedence: an explicit torchrun-style setting overrides what an
  // outer launcher (mpirun, srun) exported.
  struct Launcher {
    const char* rank;
    const char* size;
    const char* name;
  };
  static const Launcher kLaunchers[] = {
      {"RANK", "WORLD_SIZE", "torchrun variables"},
      {"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE", "Open MPI"},
      {"SLURM_PROCID", "SLURM_NTASKS", "Slurm"}};
  for (const auto& l : kLaunchers) {
    const char* rank = lookup(l.rank);
    if (!rank) continue;
    const std::string source = std::string("environment (") + l.name + ")";
    const char* size = lookup(l.size);
    if (!size)
      ThrowInputError(source, l.size, "the world size next to " + std::string(l.rank), "unset");
    DistributedConfig c;
    c.source = source;
    c.rank = ParseCount(l.rank, rank, source);
    c.world_size = ParseCount(l.size, size, source);
    if (c.world_size < 1)
      ThrowInputError(source, l.size, "at least 1 process", std::to_string(c.world_size));
    if (c.rank >= c.world_size)
      ThrowInputError(source, l.rank,
                      "a rank below " + std::string(l.size) + " = " + std::to_string(c.world_size),
                      std::to_string(c.rank));
    if (c.world_size == 1) return std::nullopt;
    const char* addr = lookup("MASTER_ADDR");
    if (!addr && std::string(l.rank) == "SLURM_PROCID") addr = lookup("SLURM_LAUNCH_NODE_IPADDR");
    if (addr && *addr) c.master_addr = addr;
    if (const char* port = lookup("MASTER_PORT")) {
      const int p = ParseCount("MASTER_PORT", port, source);
      if (p < 1 || p > 65535) ThrowInputError(source, "MASTER_PORT", "a TCP port 1..65535", port);
      c.master_port = p;
    }
    return c;
  }
  return std::nullopt;
}

}  // namespace sims::learning
