//! A monotone priority queue over integer keys for label-setting searches whose steps are
//! bounded: Dial's bucket queue (Dial, "Algorithm 360", 1969) with buckets wider than one key
//! and each bucket sorted when its turn comes. Every key pushed must lie at or above the
//! current bucket and less than `span` above it — Dijkstra's algorithm over a grid, whose
//! steps are at least one and at most √2 cells, keeps to that — so a push is O(1) and a pop
//! O(log m) for the m items of its bucket, against O(log n) for a binary heap of all n.
//!
//! Items come out in the order a binary heap of `Reverse((key, item))` gives them: by key,
//! then by item, so a search that switches to it visits cells in the same order and computes
//! the same numbers.

/// A bucket queue of `(key, item)` pairs.
#[derive(Clone, Debug)]
pub struct BucketQueue {
    /// Keys per bucket, `2^shift` (a power of two, so that a key's bucket is a shift).
    shift: u32,
    /// The buckets after the current one, round a ring of a power of two slots: bucket `b`
    /// (of keys `b·2^shift .. (b + 1)·2^shift`) in slot `b & mask`.
    ring: Vec<Vec<(u64, u32)>>,
    mask: u64,
    /// The current bucket's items, sorted largest first, so that `pop` takes the smallest.
    current: Vec<(u64, u32)>,
    /// The current bucket's number.
    at: u64,
    len: usize,
}

impl BucketQueue {
    /// A queue of buckets at most `width` keys wide (the largest power of two not above it)
    /// for pushes at most `span` keys above the current bucket's start.
    pub fn new(width: u64, span: u64) -> Self {
        let shift = 63 - width.max(1).leading_zeros();
        let slots = ((span >> shift) + 2).next_power_of_two() as usize;
        let ring = (0..slots).map(|_| Vec::new()).collect();
        Self { shift, ring, mask: slots as u64 - 1, current: Vec::new(), at: 0, len: 0 }
    }

    /// Whether the queue holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Empties the queue and lets keys start from 0 again, keeping the buckets' memory.
    pub fn clear(&mut self) {
        for b in &mut self.ring {
            b.clear();
        }
        self.current.clear();
        (self.at, self.len) = (0, 0);
    }

    /// Starts a search: `item` with `key`, at any key, into a queue just made or cleared (the
    /// current bucket moves to it, since a search's source may lie at any distance; every
    /// bucket is empty, so which one is current changes no order).
    pub fn push_source(&mut self, key: u64, item: u32) {
        assert!(self.len == 0, "bucket queue: a source pushed into a queue holding {} items", self.len);
        self.at = key >> self.shift;
        self.push(key, item);
    }

    /// Adds `item` with `key`: at or above the bucket of the last key taken (of 0 after
    /// [`Self::clear`]), less than the span above it (panics otherwise: the queue would hand
    /// items out of order or lose them).
    pub fn push(&mut self, key: u64, item: u32) {
        let b = key >> self.shift;
        assert!(
            b >= self.at && b - self.at <= self.mask,
            "bucket queue: key {key} outside buckets {}..={} of width {}",
            self.at,
            self.at + self.mask,
            1u64 << self.shift
        );
        if b == self.at {
            let at = self.current.partition_point(|&e| e > (key, item));
            self.current.insert(at, (key, item));
        } else {
            self.ring[(b & self.mask) as usize].push((key, item));
        }
        self.len += 1;
    }

    /// Takes the item of the smallest key (of the smallest item among equal keys).
    pub fn pop(&mut self) -> Option<(u64, u32)> {
        if self.len == 0 {
            return None;
        }
        while self.current.is_empty() {
            self.at += 1;
            std::mem::swap(&mut self.current, &mut self.ring[(self.at & self.mask) as usize]);
            self.current.sort_unstable_by(|a, b| b.cmp(a));
        }
        self.len -= 1;
        self.current.pop()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    #[test]
    fn a_source_may_start_at_any_key() {
        let mut queue = BucketQueue::new(1024, 140_000);
        // Past the span above bucket 0: a search's source a snap away from its cell centre.
        queue.push_source(149_817, 3);
        queue.push(149_817 + 100_000, 4);
        queue.push(149_817 + 10, 5);
        assert_eq!(queue.pop(), Some((149_817, 3)));
        assert_eq!(queue.pop(), Some((149_827, 5)));
        assert_eq!(queue.pop(), Some((249_817, 4)));
        queue.clear();
        queue.push_source(5, 1);
        assert_eq!(queue.pop(), Some((5, 1)));
    }

    #[test]
    fn it_hands_items_out_as_a_binary_heap_of_key_then_item_does() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for round in 0..60 {
            let (width, span) = [(1, 10), (7, 100), (1000, 70_000), (3, 3)][round % 4];
            let mut queue = BucketQueue::new(width, span);
            let mut binary = BinaryHeap::new();
            let mut last = 0u64;
            for _ in 0..3_000 {
                // Pushes from the last key taken to `span` above it (some equal to it, as a
                // search's ties are); now and then a pop.
                if rng.random_range(0..3) > 0 || binary.is_empty() {
                    let key = last + if rng.random_range(0..5) == 0 { 0 } else { rng.random_range(0..=span) };
                    let item = rng.random_range(0..300u32);
                    queue.push(key, item);
                    binary.push(Reverse((key, item)));
                } else {
                    let Reverse(expected) = binary.pop().unwrap();
                    assert_eq!(queue.pop(), Some(expected), "round {round}");
                    last = expected.0;
                }
            }
            while let Some(Reverse(expected)) = binary.pop() {
                assert_eq!(queue.pop(), Some(expected));
            }
            assert!(queue.is_empty() && queue.pop().is_none());
            queue.clear();
            queue.push(2, 1);
            assert_eq!(queue.pop(), Some((2, 1)), "a cleared queue starts from key 0 again");
        }
    }

    #[test]
    #[should_panic(expected = "outside buckets")]
    fn a_key_beyond_the_span_is_refused() {
        let mut q = BucketQueue::new(10, 100);
        q.push(5, 0);
        q.push(500, 1);
    }

    #[test]
    #[should_panic(expected = "outside buckets")]
    fn a_key_below_the_last_bucket_taken_is_refused() {
        let mut q = BucketQueue::new(10, 100);
        q.push(55, 0);
        q.pop();
        q.push(40, 1);
    }
}
