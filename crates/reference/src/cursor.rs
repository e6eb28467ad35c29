//! A cursor for sampling at ascending times: the index a binary search would give
//! (`partition_point`), found by walking on from the last one when the times ascend (a
//! few steps, then strides that double, then a binary search inside the last stride), so
//! a solution sampled at n ascending times pays O(n + pieces) at most and O(n·log gap)
//! for times far apart — the same index, hence the same values bit for bit, whatever
//! order the times come in.

/// Steps walked forward one at a time before the strides double.
const WALK: usize = 8;

/// The last partition point found.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Cursor(usize);

impl Cursor {
    /// `items.partition_point(below)` for a predicate `below` that is true on a prefix of
    /// `items` (as `|s| s.t <= t` on items sorted by time): walked on from the last answer
    /// when it still holds there, a binary search otherwise.
    pub(crate) fn partition_point<T>(&mut self, items: &[T], below: impl Fn(&T) -> bool) -> usize {
        let from = self.0.min(items.len());
        let i = if from > 0 && !below(&items[from - 1]) {
            items[..from].partition_point(&below)
        } else {
            let mut i = from;
            let mut steps = 0;
            while i < items.len() && below(&items[i]) {
                i += 1;
                steps += 1;
                if steps == WALK {
                    i = gallop(items, i, &below);
                    break;
                }
            }
            i
        };
        self.0 = i;
        i
    }
}

/// The partition point of `items` at or after `from` (every item before `from` is
/// below): strides of 1, 2, 4, … until one ends past it, then a binary search inside it.
fn gallop<T>(items: &[T], from: usize, below: &impl Fn(&T) -> bool) -> usize {
    let (mut low, mut stride) = (from, 1);
    let high = loop {
        let probe = low + stride;
        if probe > items.len() {
            break items.len();
        }
        if below(&items[probe - 1]) {
            low = probe;
            stride *= 2;
        } else {
            break probe - 1;
        }
    };
    low + items[low..high].partition_point(below)
}

#[cfg(test)]
mod tests {
    use super::Cursor;

    #[test]
    fn the_same_index_as_a_binary_search_in_any_order() {
        // repeated times, a jump back, long jumps forward, past both ends
        let items = [
            0.0, 0.1, 0.1, 0.2, 0.5, 0.5, 0.5, 0.9, 1.0, 1.0, 1.5, 2.0, 3.0, 4.0,
        ];
        let times = [
            -1.0, 0.0, 0.05, 0.1, 0.1, 0.3, 0.5, 0.2, 0.95, 4.0, 5.0, 0.0, 3.5, 0.1, 1.0,
        ];
        let mut cursor = Cursor::default();
        for t in times {
            let expected = items.partition_point(|&s| s <= t);
            assert_eq!(
                cursor.partition_point(&items, |&s| s <= t),
                expected,
                "t = {t}"
            );
        }
        // walks longer than WALK steps: strides that double, then a binary search
        let many: Vec<f64> = (0..100).map(f64::from).collect();
        let mut cursor = Cursor::default();
        for t in [
            0.5, 57.5, 57.5, 60.0, 61.0, 63.0, 70.5, 99.0, 120.0, 3.0, 98.5,
        ] {
            let expected = many.partition_point(|&s| s <= t);
            assert_eq!(
                cursor.partition_point(&many, |&s| s <= t),
                expected,
                "t = {t}"
            );
        }
        // every pair (from, to) of times on a half-unit grid past both ends
        let half = |k: i32| 0.5 * f64::from(k) - 5.0;
        for a in 0..=220 {
            for b in 0..=220 {
                let mut cursor = Cursor::default();
                cursor.partition_point(&many, |&s| s <= half(a));
                let expected = many.partition_point(|&s| s <= half(b));
                assert_eq!(cursor.partition_point(&many, |&s| s <= half(b)), expected);
            }
        }
    }
}
