//! Gathered photons put in the order the estimates sum them: by (squared distance, index),
//! one distinct `u64` key per photon (non-negative floats order like their bits), so every
//! correct sort gives the same order. Large gathers (the fixed-radius reads of the caustic
//! map's gather view, thousands of photons inside a caustic's focus) take an LSD radix sort
//! on the key's bytes, skipping the bytes every key shares; small ones the comparison sort.
//! Generic over the element (the kd-tree's `Neighbour`), so this module imports nothing of
//! the tree's.

/// From this many elements on, the radix sort.
const RADIX_MIN: usize = 256;

/// Sorts `found` by `key`, which is distinct for distinct elements.
pub fn sort<T: Copy>(found: &mut Vec<T>, key: impl Fn(&T) -> u64) {
    if found.len() < RADIX_MIN {
        found.sort_unstable_by_key(key);
    } else {
        radix_sort(found, key);
    }
}

/// LSD radix sort on the key's eight bytes (each pass stable), a pass only for the bytes in
/// which the keys differ.
fn radix_sort<T: Copy>(found: &mut Vec<T>, key: impl Fn(&T) -> u64) {
    let n = found.len();
    let Some(&first) = found.first() else {
        return;
    };
    let mut counts = [[0u32; 256]; 8];
    for x in found.iter() {
        let k = key(x);
        for (d, c) in counts.iter_mut().enumerate() {
            c[((k >> (8 * d)) & 0xff) as usize] += 1;
        }
    }
    let mut other = vec![first; n];
    for (d, c) in counts.iter().enumerate() {
        if c.iter().any(|&m| m as usize == n) {
            continue;
        }
        let mut next = [0u32; 256];
        let mut sum = 0;
        for (s, &m) in next.iter_mut().zip(c) {
            *s = sum;
            sum += m;
        }
        for x in found.iter() {
            let at = &mut next[((key(x) >> (8 * d)) & 0xff) as usize];
            other[*at as usize] = *x;
            *at += 1;
        }
        std::mem::swap(found, &mut other);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gathered photon's key as the kd-tree makes it.
    #[derive(Debug, Clone, Copy, PartialEq)]
    struct Neighbour {
        dist2: f32,
        index: u32,
    }

    fn key(n: &Neighbour) -> u64 {
        (u64::from(n.dist2.to_bits()) << 32) | u64::from(n.index)
    }

    /// The radix sort and the comparison sort give the same order: distances with ties
    /// (coarse values), zeros, one shared distance, indices above 2¹⁶ and 2²⁴, sizes around
    /// the threshold.
    #[test]
    fn radix_order_is_the_comparison_order() {
        let mut x = 7u64;
        let mut next = move || {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 33) as u32
        };
        for (n, coarse, spread) in [
            (RADIX_MIN, 0u32, 1u32),
            (RADIX_MIN + 1, 16, 100),
            (300, 1, 1 << 20),
            (1000, 0, 1 << 10),
            (2851, 64, 1 << 26),
            (5000, 1 << 20, 1 << 31),
        ] {
            let mut found: Vec<Neighbour> = (0..n)
                .map(|i| {
                    let v = next();
                    let dist2 = if coarse == 0 {
                        0.25
                    } else {
                        (v % coarse) as f32 * 0.01
                    };
                    Neighbour {
                        dist2,
                        index: (i as u32).wrapping_mul(2_654_435_761) % spread.max(n as u32)
                            + if i % 2 == 0 { 0 } else { spread },
                    }
                })
                .collect();
            found.dedup_by_key(|nb| nb.index);
            let mut want = found.clone();
            want.sort_unstable_by_key(key);
            radix_sort(&mut found, key);
            assert_eq!(found, want, "{n} photons");
        }
    }
}
