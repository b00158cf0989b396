// SPDX-License-Identifier: Apache-2.0
// ARTCAM_MAX_MEMORY_MB (core/util/memory_budget.h): a number of MiB > 0 sets the budget; any
// other value is reported in one line naming the variable (and the budget stays the machine's),
// never ignored in silence; set to nothing is unset.
#include "core/util/memory_budget.h"

#include <QtTest/QtTest>

using namespace artcam;

class TestMemoryBudget : public QObject {
  Q_OBJECT

 private slots:
  void cleanup() { qunsetenv("ARTCAM_MAX_MEMORY_MB"); }

  void aNumberOfMibSetsTheBudget() {
    qputenv("ARTCAM_MAX_MEMORY_MB", "50");
    QCOMPARE(memoryBudgetBytes(), 50.0 * 1024 * 1024);
    QCOMPARE(memoryBudgetProblem(), std::string());
    QCOMPARE(describeMemoryBudget(),
             std::string("the memory budget of 50.0 MiB (ARTCAM_MAX_MEMORY_MB)"));
    qputenv("ARTCAM_MAX_MEMORY_MB", "1.5e3");
    QCOMPARE(memoryBudgetBytes(), 1500.0 * 1024 * 1024);
  }

  void anyOtherValueIsReportedNamingTheVariable_data() {
    QTest::addColumn<QByteArray>("value");
    for (const char* v : {"abc", "0", "-5", "12MB", " 12", "nan", "inf", "1e999"})
      QTest::newRow(v) << QByteArray(v);
  }
  void anyOtherValueIsReportedNamingTheVariable() {
    QFETCH(QByteArray, value);
    qunsetenv("ARTCAM_MAX_MEMORY_MB");
    const double machine = memoryBudgetBytes();
    qputenv("ARTCAM_MAX_MEMORY_MB", value);
    const std::string problem = memoryBudgetProblem();
    QCOMPARE(problem, "ARTCAM_MAX_MEMORY_MB=" + value.toStdString() +
                          ": expected a number of MiB greater than 0 (unset it for half this "
                          "machine's memory)");
    QCOMPARE(memoryBudgetBytes(), machine);
    QVERIFY(describeMemoryBudget().find("half this machine's memory") != std::string::npos);
  }

  void setToNothingIsUnset() {
    qputenv("ARTCAM_MAX_MEMORY_MB", "");
    QCOMPARE(memoryBudgetProblem(), std::string());
  }
};

QTEST_GUILESS_MAIN(TestMemoryBudget)
#include "test_memory_budget.moc"
