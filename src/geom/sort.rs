//! Sorting by a float key through one copy of the sort. Every `sort_by` with its own closure
//! is another few kilobytes of quicksort in the page's module (the largest item in it, before
//! these); a float key sorted through here costs one copy for the whole crate. Ties keep their
//! order, as `sort_by` does, so a call moved here gives the same order.

/// Sorts floats ascending in IEEE total order (`f64::total_cmp`).
pub fn sort_floats(v: &mut [f64]) {
    // Equal under total order means the same bits: stable and unstable agree.
    v.sort_unstable_by(f64::total_cmp);
}

/// The indices of `keys` in ascending total order; equal keys keep their order.
pub fn order_by(keys: &[f64]) -> Vec<usize> {
    let mut pairs: Vec<(f64, usize)> = keys.iter().copied().zip(0..).collect();
    pairs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    pairs.into_iter().map(|(_, i)| i).collect()
}

/// Sorts `v` ascending by `key` (descending: negate it), stable, as
/// `v.sort_by(|a, b| key(a).total_cmp(&key(b)))` does.
pub fn sort_by_float<T>(v: &mut [T], key: impl Fn(&T) -> f64) {
    let keys: Vec<f64> = v.iter().map(key).collect();
    let mut order = order_by(&keys);
    // Position k takes what stood at order[k]: follow each cycle of the permutation.
    for start in 0..v.len() {
        let mut k = start;
        while order[k] != usize::MAX {
            let from = order[k];
            order[k] = usize::MAX;
            if from == start {
                break;
            }
            v.swap(k, from);
            k = from;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_order_as_a_stable_sort_by_with_ties_and_negative_zero() {
        let mut seed = 7u64;
        for n in [0usize, 1, 2, 5, 40, 300] {
            let v: Vec<(f64, usize)> = (0..n)
                .map(|i| {
                    seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    let k = [(seed >> 40) as f64 % 7.0, -0.0, 0.0, f64::INFINITY][(seed >> 20) as usize % 4];
                    (k, i)
                })
                .collect();
            let mut want = v.clone();
            want.sort_by(|a, b| b.0.total_cmp(&a.0));
            let mut got = v.clone();
            sort_by_float(&mut got, |a| -a.0);
            assert_eq!(got, want);
            let mut floats: Vec<f64> = v.iter().map(|a| a.0).collect();
            let mut want: Vec<f64> = floats.clone();
            crate::geom::sort::sort_floats(&mut want);
            sort_floats(&mut floats);
            assert_eq!(floats.iter().map(|f| f.to_bits()).collect::<Vec<_>>(), want.iter().map(|f| f.to_bits()).collect::<Vec<_>>());
        }
    }
}
