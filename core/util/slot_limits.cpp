// SPDX-License-Identifier: Apache-2.0
#include "core/util/slot_limits.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include <sched.h>

namespace artcam {

namespace {

std::string_view trimmed(std::string_view text) {
  const auto space = [](char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; };
  while (!text.empty() && space(text.front())) text.remove_prefix(1);
  while (!text.empty() && space(text.back())) text.remove_suffix(1);
  return text;
}

std::optional<double> positiveNumber(std::string_view text) {
  unsigned long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value == 0) return std::nullopt;
  return static_cast<double>(value);
}

std::optional<std::string> fileText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void keepSmaller(std::optional<double>& kept, std::optional<double> value) {
  if (value && (!kept || *value < *kept)) kept = value;
}

}  // namespace

std::optional<double> cpuQuotaFromCpuMax(std::string_view text) {
  text = trimmed(text);
  const size_t space = text.find(' ');
  if (space == std::string_view::npos) return std::nullopt;
  const auto quota = positiveNumber(text.substr(0, space));  // "max": none
  const auto period = positiveNumber(trimmed(text.substr(space + 1)));
  if (!quota || !period) return std::nullopt;
  return *quota / *period;
}

std::optional<double> memoryFromMemoryMax(std::string_view text) {
  return positiveNumber(trimmed(text));  // "max": none
}

std::string cgroupPathFromProcText(std::string_view text) {
  while (!text.empty()) {
    const size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    if (line.rfind("0::", 0) == 0) return std::string(trimmed(line.substr(3)));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return "";
}

SlotLimits readSlotLimits(const std::string& cgroup_root, const std::string& cgroup_path) {
  SlotLimits limits;
  std::string path = cgroup_path;
  while (!path.empty() && path.back() == '/') path.pop_back();
  // The process's own cgroup, then each one above it; the root's files (absent on a host) last.
  for (;;) {
    const std::string folder = cgroup_root + path;
    if (const auto text = fileText(folder + "/cpu.max"))
      keepSmaller(limits.cpus, cpuQuotaFromCpuMax(*text));
    if (const auto text = fileText(folder + "/memory.max"))
      keepSmaller(limits.memory_bytes, memoryFromMemoryMax(*text));
    if (path.empty()) break;
    path.erase(path.rfind('/'));
  }
  return limits;
}

int slotThreads(std::optional<double> cpus, int affinity_cpus, int machine_cpus) {
  int threads = affinity_cpus > 0 ? affinity_cpus : std::max(1, machine_cpus);
  if (cpus) threads = std::min(threads, static_cast<int>(std::ceil(*cpus - 1e-9)));
  return std::max(1, threads);
}

const SlotLimits& processSlotLimits() {
  static const SlotLimits limits = [] {
    const auto proc = fileText("/proc/self/cgroup");
    if (!proc) return SlotLimits{};
    return readSlotLimits("/sys/fs/cgroup", cgroupPathFromProcText(*proc));
  }();
  return limits;
}

int affinityCpuCount() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

int slotThreadCount() {
  static const int threads = slotThreads(processSlotLimits().cpus, affinityCpuCount(),
                                         static_cast<int>(std::thread::hardware_concurrency()));
  return threads;
}

}  // namespace artcam
