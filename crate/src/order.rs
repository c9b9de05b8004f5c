//! Stable sorts by one `f64` key, compiled once for the whole crate (issue #29).
//!
//! `slice::sort_by` is generic over its comparator and every closure is a type of its
//! own, so each call site compiled its own merge sort: the page's first-screen wasm held
//! 92 sort functions, 46 KB before gzip. The crate's sorts by one `f64` key go through
//! [`sorted_order`] instead, the one place that sorts: the permutation that puts the keys
//! in ascending [`f64::total_cmp`] order, stable (equal keys keep their order). A stable
//! sort's result is unique for a given order, so [`sort_by_f64_key`] gives exactly what
//! `items.sort_by(|a, b| key(a).total_cmp(&key(b)))` gave: the same items in the same
//! places, bit for bit. For a descending sort, sort by the negated key: `total_cmp` of
//! the negated values is exactly the reverse order (negation flips the sign bit, which
//! maps `total_cmp`'s integer key `k` to `-1 - k`).

/// The stable ascending order of `keys` by [`f64::total_cmp`]: `order[0]` is the index
/// of the smallest key, and equal keys keep their order.
pub fn sorted_order(keys: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by(|&a, &b| keys[a].total_cmp(&keys[b]));
    order
}

/// Sorts `items` stably by `key` ascending ([`f64::total_cmp`]), as
/// `items.sort_by(|a, b| key(a).total_cmp(&key(b)))` does (the key read once per item).
pub fn sort_by_f64_key<T>(items: &mut [T], key: impl Fn(&T) -> f64) {
    let keys: Vec<f64> = items.iter().map(key).collect();
    permute(items, &sorted_order(&keys));
}

/// Moves `items` into `order` (a permutation of their indices): afterwards `items[k]`
/// is what `items[order[k]]` was. In place, following each cycle once.
fn permute<T>(items: &mut [T], order: &[usize]) {
    // dest[i]: where the item now at i belongs.
    let mut dest = vec![0; order.len()];
    for (k, &i) in order.iter().enumerate() {
        dest[i] = k;
    }
    for i in 0..items.len() {
        while dest[i] != i {
            let j = dest[i];
            items.swap(i, j);
            dest.swap(i, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same result as `sort_by` on the key, ties and signed zeros and NaNs included.
    #[test]
    fn sorts_as_sort_by_does_stably() {
        let keys = [
            3.0,
            -0.0,
            1.0,
            0.0,
            f64::NAN,
            1.0,
            -2.5,
            f64::INFINITY,
            -f64::NAN,
            1.0,
            -0.0,
        ];
        let mut want: Vec<(f64, usize)> = keys.iter().copied().zip(0..).collect();
        want.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut got: Vec<(f64, usize)> = keys.iter().copied().zip(0..).collect();
        sort_by_f64_key(&mut got, |p| p.0);
        assert_eq!(
            got.iter().map(|p| p.1).collect::<Vec<_>>(),
            want.iter().map(|p| p.1).collect::<Vec<_>>()
        );
        // Descending by the negated key: the reverse total order, ties still in order.
        let mut want: Vec<(f64, usize)> = keys.iter().copied().zip(0..).collect();
        want.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut got: Vec<(f64, usize)> = keys.iter().copied().zip(0..).collect();
        sort_by_f64_key(&mut got, |p| -p.0);
        assert_eq!(
            got.iter().map(|p| p.1).collect::<Vec<_>>(),
            want.iter().map(|p| p.1).collect::<Vec<_>>()
        );
        let mut empty: Vec<f64> = Vec::new();
        sort_by_f64_key(&mut empty, |x| *x);
        assert!(empty.is_empty());
    }

    /// Every permutation of five items lands each item where the order says.
    #[test]
    fn permutes_every_order_of_five() {
        let mut order = [0, 1, 2, 3, 4];
        let mut count = 0;
        // Heap's algorithm over all 120 orders.
        let mut c = [0usize; 5];
        let mut check = |o: &[usize]| {
            let mut items = ['a', 'b', 'c', 'd', 'e'];
            let before = items;
            permute(&mut items, o);
            for (k, &i) in o.iter().enumerate() {
                assert_eq!(items[k], before[i], "order {o:?}");
            }
            count += 1;
        };
        check(&order);
        let mut i = 0;
        while i < 5 {
            if c[i] < i {
                order.swap(if i % 2 == 0 { 0 } else { c[i] }, i);
                check(&order);
                c[i] += 1;
                i = 0;
            } else {
                c[i] = 0;
                i += 1;
            }
        }
        assert_eq!(count, 120);
    }
}
