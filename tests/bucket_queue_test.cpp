#include <growth/bucket_queue.h>

#include <gtest/gtest.h>

using growth::BucketQueue;

TEST(BucketQueue, EmptyQueue) {
  BucketQueue<int> q(3);
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.size(), 0u);
  EXPECT_EQ(q.topLevel(), 3);
}

TEST(BucketQueue, PopsMostUrgentLevelFirstAndFifoWithinALevel) {
  BucketQueue<int> q(4);
  q.push(2, 20);
  q.push(3, 30);
  q.push(2, 21);
  q.push(0, 0);
  q.push(2, 22);
  int level = -1;
  EXPECT_EQ(q.pop(&level), 0);
  EXPECT_EQ(level, 0);
  EXPECT_EQ(q.pop(&level), 20);
  EXPECT_EQ(level, 2);
  // A more urgent item pushed later overtakes the remaining ones.
  q.push(1, 10);
  EXPECT_EQ(q.pop(), 10);
  EXPECT_EQ(q.pop(), 21);
  EXPECT_EQ(q.pop(), 22);
  EXPECT_EQ(q.pop(&level), 30);
  EXPECT_EQ(level, 3);
  EXPECT_TRUE(q.empty());
}

TEST(BucketQueue, LongFifoKeepsOrderAcrossCompaction) {
  BucketQueue<int> q(2);
  int next = 0;
  for (int i = 0; i < 20000; ++i) q.push(1, i);
  // Interleave pops and pushes so the consumed prefix gets dropped several times.
  for (int round = 0; round < 30000; ++round) {
    ASSERT_EQ(q.pop(), next++);
    q.push(1, 20000 + round);
  }
  while (!q.empty()) ASSERT_EQ(q.pop(), next++);
  EXPECT_EQ(next, 50000);
}

TEST(BucketQueue, ClearEmptiesEveryLevel) {
  BucketQueue<int> q(3);
  q.push(0, 1);
  q.push(2, 2);
  q.clear();
  EXPECT_TRUE(q.empty());
  q.push(1, 5);
  EXPECT_EQ(q.pop(), 5);
}
