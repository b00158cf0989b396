// SPDX-License-Identifier: Apache-2.0
// Scratch blocks (core/util/scratch.h): a released block is handed out again, only for
// requests it fits without being more than twice their size, within the pool's limits.
#include "core/util/scratch.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

using namespace artcam;

class TestScratch : public QObject {
  Q_OBJECT

 private slots:
  void releasedBlockIsReused() {
    void* first = nullptr;
    {
      ScratchBlock a = takeScratch(3 << 20);
      QVERIFY(a.data() != nullptr);
      QVERIFY(a.bytes() >= (3u << 20));
      QCOMPARE(reinterpret_cast<std::uintptr_t>(a.data()) % 64, std::uintptr_t{0});
      std::memset(a.data(), 1, a.bytes());  // the memory is usable
      first = a.data();
    }
    QVERIFY(scratchKeptBytes() >= (3u << 20));
    // A request it fits takes the same block; while it is out, another request gets a new one.
    ScratchBlock b = takeScratch(2 << 20);
    QCOMPARE(b.data(), first);
    ScratchBlock c = takeScratch(2 << 20);
    QVERIFY(c.data() != first);
  }

  void smallRequestLeavesLargeBlock() {
    void* large = nullptr;
    {
      ScratchBlock a = takeScratch(8 << 20);
      large = a.data();
    }
    ScratchBlock small = takeScratch(1 << 20);  // an eighth: not worth holding 8 MiB
    QVERIFY(small.data() != large);
    ScratchBlock again = takeScratch(5 << 20);
    QCOMPARE(again.data(), large);
  }

  // Twice the blocks the pool keeps, released together: at most kScratchKeepBlocks of them come
  // back (the rest were freed), and a block over the byte limit is never kept.
  void poolStaysWithinLimits() {
    std::vector<void*> released;
    {
      std::vector<ScratchBlock> blocks;
      for (int k = 0; k < 2 * kScratchKeepBlocks; ++k) {
        blocks.push_back(takeScratch(std::size_t{1} << 20));
        released.push_back(blocks.back().data());
      }
      ScratchBlock huge = takeScratch(kScratchKeepBytes + 1);
      QVERIFY(huge.data() != nullptr);
    }
    QVERIFY(scratchKeptBytes() <= kScratchKeepBytes);
    std::vector<ScratchBlock> again;
    int reused = 0;
    for (int k = 0; k < 2 * kScratchKeepBlocks; ++k) {
      again.push_back(takeScratch(std::size_t{1} << 20));
      reused += std::find(released.begin(), released.end(), again.back().data()) != released.end() ? 1 : 0;
    }
    QVERIFY(reused >= 1);
    QVERIFY2(reused <= kScratchKeepBlocks, qPrintable(QString::number(reused)));
    QVERIFY(takeScratch(0).data() == nullptr);
  }

  void threadsShareThePool() {
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([] {
        for (int k = 0; k < 200; ++k) {
          ScratchBlock b = takeScratch(std::size_t{64} << 10 << (k % 4));
          static_cast<unsigned char*>(b.data())[0] = 1;
        }
      });
    for (std::thread& t : threads) t.join();
    QVERIFY(scratchKeptBytes() <= kScratchKeepBytes);
  }
};

QTEST_GUILESS_MAIN(TestScratch)
#include "test_scratch.moc"
