// SPDX-License-Identifier: Apache-2.0
// The CPUs and memory this process may use: its slot on a render farm, a container's limits,
// `taskset`. The machine's totals (std::thread::hardware_concurrency, _SC_PHYS_PAGES) overstate
// them, and a render that starts more threads than its slot has CPUs is throttled by the
// scheduler (the cgroup's quota runs out within each period, every thread waits), one that
// plans for more memory than its slot has is killed by the OOM killer.
//
// Decisions:
// - CPUs: the CPUs in the affinity mask (sched_getaffinity), capped by the cgroup v2 CPU quota
//   `cpu.max` ("QUOTA PERIOD", or "max PERIOD" for none) of the process's cgroup and of every
//   cgroup above it, quota/period rounded up (a slot of 1.5 CPUs gets 2 threads: the half CPU
//   is used, and one extra thread costs little), at least 1.
// - Memory: the smallest cgroup v2 `memory.max` of the process's cgroup and those above it
//   ("max": none).
// - cgroup v1 is not read (systems of this project's age use v2); no limit then, as before.
// The parsing takes the files' texts and the cgroup root, so tests give made-up cgroups.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace artcam {

// A cpu.max text ("150000 100000\n") as a number of CPUs (1.5); nullopt for "max …" or a text
// that does not parse (no limit is assumed rather than a wrong one).
std::optional<double> cpuQuotaFromCpuMax(std::string_view text);

// A memory.max text ("1073741824\n") in bytes; nullopt for "max" or a text that does not parse.
std::optional<double> memoryFromMemoryMax(std::string_view text);

// The cgroup v2 path of this process from /proc/self/cgroup's text (its "0::/PATH" line):
// "/PATH", or "" when there is no v2 line.
std::string cgroupPathFromProcText(std::string_view proc_self_cgroup);

struct SlotLimits {
  std::optional<double> cpus;          // the smallest CPU quota on the way to the root
  std::optional<double> memory_bytes;  // the smallest memory.max on the way to the root
};

// The limits of the cgroup `cgroup_path` ("/a/b") under the mounted hierarchy `cgroup_root`
// ("/sys/fs/cgroup"), reading cpu.max and memory.max in it and each folder above it up to the
// root. Missing or unreadable files are no limit.
SlotLimits readSlotLimits(const std::string& cgroup_root, const std::string& cgroup_path);

// The threads a quota of `cpus` CPUs and an affinity mask of `affinity_cpus` CPUs (0: unknown)
// allow: min(affinity, ceil(cpus)), at least 1; `machine_cpus` when neither says.
int slotThreads(std::optional<double> cpus, int affinity_cpus, int machine_cpus);

// This process's slot: /proc/self/cgroup under /sys/fs/cgroup, read once and kept.
const SlotLimits& processSlotLimits();
// The CPUs in this process's affinity mask (sched_getaffinity), 0 when it cannot be read.
int affinityCpuCount();
// The threads "all cores" means for this process: slotThreads over the above (read once).
int slotThreadCount();

}  // namespace artcam
