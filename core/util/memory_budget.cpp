// SPDX-License-Identifier: Apache-2.0
#include "core/util/memory_budget.h"

#include "core/util/slot_limits.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <system_error>

#include <unistd.h>

namespace artcam {

namespace {

constexpr char kVariable[] = "ARTCAM_MAX_MEMORY_MB";

// The variable's value in MiB when it is set to a number > 0 (the whole text a decimal, read
// locale-free: the studio runs under the user's locale), else nullopt; `set` says whether it
// was set at all.
std::optional<double> budgetFromEnvironment(bool* set) {
  const char* text = std::getenv(kVariable);
  *set = text != nullptr && *text != '\0';  // set to nothing is unset, as shells treat it
  if (!*set) return std::nullopt;
  const char* end = text + std::strlen(text);
  double mb = 0.0;
  const auto [stop, error] = std::from_chars(text, end, mb);
  if (error != std::errc() || stop != end || !(mb > 0.0) || !std::isfinite(mb)) return std::nullopt;
  return mb;
}

// The memory of this process's slot: its cgroup's memory.max when that is below the machine's
// physical memory (slot_limits.h); `limited` says it was.
double machineBudgetBytes(bool* limited = nullptr) {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  double memory = pages <= 0 || page <= 0
                      ? 8.0 * 1024.0 * 1024.0 * 1024.0  // unknown: a 4 GiB budget
                      : static_cast<double>(pages) * static_cast<double>(page);
  const std::optional<double> slot = processSlotLimits().memory_bytes;
  if (limited) *limited = slot && *slot < memory;
  if (slot && *slot < memory) memory = *slot;
  return 0.5 * memory;
}

}  // namespace

double memoryBudgetBytes() {
  bool set = false;
  if (const std::optional<double> mb = budgetFromEnvironment(&set)) return *mb * 1024.0 * 1024.0;
  return machineBudgetBytes();
}

std::string describeMemoryBudget() {
  bool set = false;
  const bool from_variable = budgetFromEnvironment(&set).has_value();
  bool limited = false;
  machineBudgetBytes(&limited);
  return "the memory budget of " + describeBytes(memoryBudgetBytes()) +
         (from_variable ? std::string(" (") + kVariable + ")"
          : limited
              ? std::string(" (half this process's cgroup memory.max; ") + kVariable + " sets it)"
              : std::string(" (half this machine's memory; ") + kVariable + " sets it)");
}

std::string memoryBudgetProblem() {
  bool set = false;
  if (budgetFromEnvironment(&set) || !set) return "";
  std::string value = std::getenv(kVariable);
  if (value.size() > 40) value = value.substr(0, 37) + "...";
  for (char& c : value)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return std::string(kVariable) + "=" + value +
         ": expected a number of MiB greater than 0 (unset it for half this machine's memory)";
}

std::string describeBytes(double bytes) {
  char text[48];
  if (bytes < 1024.0 * 1024.0 * 1024.0)
    std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1024.0 * 1024.0));
  else
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return text;
}

std::string notEnoughMemoryFor(std::int64_t width, std::int64_t height, double bytes_per_pixel) {
  const double bytes = static_cast<double>(width) * static_cast<double>(height) * bytes_per_pixel;
  return "not enough memory for " + std::to_string(width) + "×" + std::to_string(height) + " (" +
         describeBytes(bytes) + ")";
}

}  // namespace artcam
