// SPDX-License-Identifier: Apache-2.0
// The slot's limits (core/util/slot_limits.h) from made-up cgroup v2 files: cpu.max's
// "QUOTA PERIOD" as quota/period CPUs rounded up, "max" as no limit, the smallest limit on the
// way to the root, memory.max in bytes. The expected values are the files' own numbers
// (the kernel's cgroup-v2 documentation gives the formats).
#include "core/util/slot_limits.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QTemporaryDir>

using namespace artcam;

namespace {

bool writeText(const QString& path, const QByteArray& text) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(text) == text.size();
}

}  // namespace

class TestSlotLimits : public QObject {
  Q_OBJECT

 private slots:
  void cpuMaxTexts() {
    QCOMPARE(cpuQuotaFromCpuMax("150000 100000\n"), std::optional<double>(1.5));
    QCOMPARE(cpuQuotaFromCpuMax("400000 100000"), std::optional<double>(4.0));
    QCOMPARE(cpuQuotaFromCpuMax("50000 100000\n"), std::optional<double>(0.5));
    QVERIFY(!cpuQuotaFromCpuMax("max 100000\n"));
    QVERIFY(!cpuQuotaFromCpuMax(""));
    QVERIFY(!cpuQuotaFromCpuMax("150000"));
    QVERIFY(!cpuQuotaFromCpuMax("abc 100000"));
    QVERIFY(!cpuQuotaFromCpuMax("100000 0"));
  }

  void memoryMaxTexts() {
    QCOMPARE(memoryFromMemoryMax("1073741824\n"), std::optional<double>(1073741824.0));
    QVERIFY(!memoryFromMemoryMax("max\n"));
    QVERIFY(!memoryFromMemoryMax("12k"));
    QVERIFY(!memoryFromMemoryMax(""));
  }

  void procSelfCgroup() {
    QCOMPARE(cgroupPathFromProcText("0::/user.slice/user-1000.slice/session-2.scope\n"),
             std::string("/user.slice/user-1000.slice/session-2.scope"));
    // A hybrid system lists v1 controllers first; only the v2 line ("0::") counts.
    QCOMPARE(cgroupPathFromProcText("12:cpu,cpuacct:/farm\n0::/farm/slot3\n"),
             std::string("/farm/slot3"));
    QCOMPARE(cgroupPathFromProcText("0::/\n"), std::string("/"));
    QCOMPARE(cgroupPathFromProcText("4:memory:/x\n"), std::string());
  }

  // A farm: the slot's parent caps CPUs at 2, the slot itself caps memory at 1 GiB; the root
  // has no limit files (as on a host). The smallest limit on the way up holds.
  void theSmallestLimitOnTheWayToTheRoot() {
    QTemporaryDir root;
    QVERIFY(root.isValid());
    QVERIFY(QDir(root.path()).mkpath("farm/slot3"));
    QVERIFY(writeText(root.filePath("farm/cpu.max"), "200000 100000\n"));
    QVERIFY(writeText(root.filePath("farm/memory.max"), "max\n"));
    QVERIFY(writeText(root.filePath("farm/slot3/cpu.max"), "max 100000\n"));
    QVERIFY(writeText(root.filePath("farm/slot3/memory.max"), "1073741824\n"));
    const SlotLimits slot = readSlotLimits(root.path().toStdString(), "/farm/slot3");
    QCOMPARE(slot.cpus, std::optional<double>(2.0));
    QCOMPARE(slot.memory_bytes, std::optional<double>(1073741824.0));
    // A tighter quota below wins over the parent's.
    QVERIFY(writeText(root.filePath("farm/slot3/cpu.max"), "150000 100000\n"));
    QCOMPARE(readSlotLimits(root.path().toStdString(), "/farm/slot3/").cpus,
             std::optional<double>(1.5));
    // No files anywhere: no limits.
    QTemporaryDir empty;
    const SlotLimits none = readSlotLimits(empty.path().toStdString(), "/a/b");
    QVERIFY(!none.cpus);
    QVERIFY(!none.memory_bytes);
  }

  void threadsFromQuotaAndAffinity() {
    QCOMPARE(slotThreads(1.5, 8, 16), 2);  // rounded up
    QCOMPARE(slotThreads(2.0, 8, 16), 2);  // exact quota: not one more
    QCOMPARE(slotThreads(0.2, 8, 16), 1);  // at least 1
    QCOMPARE(slotThreads(4.0, 1, 16), 1);  // the affinity mask is smaller
    QCOMPARE(slotThreads(std::nullopt, 3, 16), 3);
    QCOMPARE(slotThreads(std::nullopt, 0, 16), 16);  // nothing known: the machine's
    QCOMPARE(slotThreads(std::nullopt, 0, 0), 1);
  }

  // This process: never more threads than its affinity mask has CPUs.
  void thisProcessKeepsToItsAffinity() {
    const int affinity = affinityCpuCount();
    QVERIFY(affinity >= 1);
    QVERIFY(slotThreadCount() >= 1);
    QVERIFY(slotThreadCount() <= affinity);
  }
};

QTEST_GUILESS_MAIN(TestSlotLimits)
#include "test_slot_limits.moc"
