//! Large build buffers on transparent huge pages where the system offers them.
//!
//! The BVH build writes a few hundred megabytes of fresh memory for a million triangles
//! (triangle boxes, the binary hierarchy, the collapse's decision table, the 8-wide nodes,
//! the triangles in BVH order). On 4 KiB pages every first touch is a page fault, and on a
//! shared host those faults took about a tenth of a one-thread build (`docs/ray-layer.md`,
//! session 11). Where transparent huge pages are in `madvise` mode (common on servers), asking
//! for them turns 512 faults into one. It is a hint only: contents, layout and results do not
//! change, and elsewhere (other systems, THP off, small buffers) nothing happens.

/// Buffers below this size are left alone (they span at most one aligned huge page).
const MIN_BYTES: usize = 4 << 20;

/// The huge page size the hint aligns to.
const HUGE_PAGE: usize = 2 << 20;

/// An empty vector with room for `n` elements whose memory is advised to use huge pages
/// (before anything touches it, so the first writes fault in whole huge pages).
pub(crate) fn vec_with_capacity<T>(n: usize) -> Vec<T> {
    let v = Vec::with_capacity(n);
    advise(&v);
    v
}

/// `n` copies of `value` in a vector on huge pages (see [`vec_with_capacity`]).
pub(crate) fn vec_filled<T: Clone>(value: T, n: usize) -> Vec<T> {
    let mut v = vec_with_capacity(n);
    v.resize(n, value);
    v
}

/// Advises the huge-page-aligned part of `v`'s allocation to use huge pages.
#[cfg(target_os = "linux")]
fn advise<T>(v: &Vec<T>) {
    let bytes = v.capacity() * std::mem::size_of::<T>();
    if bytes < MIN_BYTES {
        return;
    }
    let start = v.as_ptr() as usize;
    let (lo, hi) = (
        start.next_multiple_of(HUGE_PAGE),
        (start + bytes) / HUGE_PAGE * HUGE_PAGE,
    );
    if hi > lo {
        // SAFETY: `lo..hi` lies inside the vector's own allocation and is page-aligned;
        // MADV_HUGEPAGE changes how the kernel backs those pages, never their contents or
        // the mapping's validity. A failure (THP unsupported) only means the hint is ignored.
        unsafe {
            libc::madvise(lo as *mut libc::c_void, hi - lo, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise<T>(_: &Vec<T>) {}

#[cfg(test)]
mod tests {
    use super::*;

    /// The buffers hold what they are given, small or large.
    #[test]
    fn buffers_hold_their_values() {
        let small = vec_filled(7u32, 10);
        assert_eq!(small, vec![7u32; 10]);
        let n = 3 * MIN_BYTES / 4 + 5;
        let large = vec_filled(0xabu8, n);
        assert_eq!(large.len(), n);
        assert!(large.iter().all(|&b| b == 0xab));
        let mut empty = vec_with_capacity::<u64>(MIN_BYTES);
        assert!(empty.is_empty() && empty.capacity() >= MIN_BYTES);
        empty.extend(0..5);
        assert_eq!(empty, [0, 1, 2, 3, 4]);
    }
}
