#include "bench/machine.hpp"

#include <sched.h>
#include <unistd.h>

#include <fstream>
#include <thread>

namespace eco::bench {
namespace {

int pinned_core = -1;

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown CPU";
}

}  // namespace

std::string describe_machine() {
  std::string s = cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores";
  if (pinned_core >= 0) s += ", pinned to core " + std::to_string(pinned_core);
  return s;
}

int pin_to_one_core() {
  const int core = sched_getcpu();
  if (core < 0) return -1;
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(core, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0) return -1;
  pinned_core = core;
  return core;
}

}  // namespace eco::bench
