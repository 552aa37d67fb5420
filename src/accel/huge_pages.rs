//! Transparent huge pages for the hierarchy's kept arrays (Linux): the wide nodes and the
//! triangles in BVH order are allocated with `madvise(MADV_HUGEPAGE)` before they are
//! written, so that the kernel backs them with 2 MiB pages where it can (THP in `madvise`
//! mode, the common default). Embree advises its BVH memory the same way.
//!
//! * **Traversal**: incoherent traversal of a large mesh is bound by TLB misses otherwise:
//!   4 KiB pages give the second-level TLB about 8 MiB of reach, against 70 MB of nodes and
//!   triangles for a million-triangle mesh (the anchor's incoherent closest hits: 1.45–1.62
//!   Mrays per CPU-second without the advice, 1.88–1.97 with it; session 36).
//! * **Not the build's temporaries** (the triangle boxes, the binary hierarchy, the
//!   collapse's decision table: 4 KiB pages). A fresh 2 MiB page costs far more to fault in
//!   than the 4 KiB pages a process gets back from the ones just freed — on this project's
//!   virtual machines, whose free memory goes back to the host, a single render of an
//!   8.3 M-triangle scene built in 11.0–12.8 s with its temporaries advised and 6.9–7.6 s
//!   without (session 36 in `docs/ray-layer.md`; session 25 had measured the advice on the
//!   temporaries as a gain inside the benchmark's process, which reuses its memory).
//!
//! Only a hint: contents and results are the same with or without it.
//! `STAGELIGHT_HUGE_PAGES=off` withholds the advice, for measuring.

/// Arrays smaller than this are left alone (they hold at most one whole 2 MiB page).
const MIN_BYTES: usize = 4 << 20;

/// The huge page size the advice is aligned to.
const HUGE: usize = 2 << 20;

/// An empty vector with room for `len` elements whose whole 2 MiB pages are advised as huge.
pub(crate) fn with_capacity<T>(len: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(len);
    if enabled() {
        advise(
            v.as_ptr().cast(),
            len.saturating_mul(std::mem::size_of::<T>()),
        );
    }
    v
}

/// False when `STAGELIGHT_HUGE_PAGES=off` (read once).
fn enabled() -> bool {
    static ENABLED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ENABLED.get_or_init(|| std::env::var("STAGELIGHT_HUGE_PAGES").as_deref() != Ok("off"))
}

/// The whole huge pages inside `[start, start + bytes)`, as (first, length); none for small
/// or short ranges.
fn huge_range(start: usize, bytes: usize) -> Option<(usize, usize)> {
    if bytes < MIN_BYTES {
        return None;
    }
    let first = start.checked_next_multiple_of(HUGE)?;
    let end = start.checked_add(bytes)? & !(HUGE - 1);
    (end > first).then(|| (first, end - first))
}

/// Advises the whole huge pages of `[start, start + bytes)`; true when the kernel accepted.
#[cfg(target_os = "linux")]
fn advise(start: *const u8, bytes: usize) -> bool {
    let Some((first, len)) = huge_range(start as usize, bytes) else {
        return false;
    };
    let Some(p) = std::ptr::NonNull::new(first as *mut std::ffi::c_void) else {
        return false;
    };
    // SAFETY: the range lies inside one live allocation of the caller's; MADV_HUGEPAGE only
    // changes how the kernel backs those pages, never their contents. A failure (a kernel
    // without THP) is harmless: the pages stay 4 KiB.
    unsafe { nix::sys::mman::madvise(p, len, nix::sys::mman::MmapAdvise::MADV_HUGEPAGE) }.is_ok()
}

#[cfg(not(target_os = "linux"))]
fn advise(_: *const u8, _: usize) -> bool {
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_whole_huge_pages_of_large_ranges_are_advised() {
        assert_eq!(huge_range(0, MIN_BYTES - 1), None);
        assert_eq!(huge_range(0, MIN_BYTES), Some((0, MIN_BYTES)));
        // Unaligned start: from the next 2 MiB boundary to the last one inside.
        assert_eq!(huge_range(HUGE + 5, 2 * HUGE + 10), Some((2 * HUGE, HUGE)));
        assert_eq!(huge_range(HUGE + 5, 2 * HUGE - 10), None);
        assert_eq!(huge_range(usize::MAX - 10, MIN_BYTES), None);
    }

    /// The advice reaches the kernel: the mapping holding a large array carries the
    /// huge-page flag (`hg` in `/proc/self/smaps`'s `VmFlags`), whether or not the kernel
    /// then finds 2 MiB pages for it.
    #[cfg(target_os = "linux")]
    #[test]
    fn large_arrays_are_advised_as_huge() {
        let v: Vec<u64> = with_capacity(3 << 20);
        let at = v.as_ptr() as usize;
        if !advise(v.as_ptr().cast(), 3 << 23) {
            eprintln!("kernel without transparent huge pages: nothing to check");
            return;
        }
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
        let mut inside = false;
        let mut flags = None;
        for line in smaps.lines() {
            if let Some((range, _)) = line.split_once(' ') {
                if let Some((lo, hi)) = range.split_once('-') {
                    if let (Ok(lo), Ok(hi)) =
                        (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
                    {
                        inside = lo <= at + HUGE && at + HUGE < hi;
                        continue;
                    }
                }
            }
            if inside {
                if let Some(f) = line.strip_prefix("VmFlags:") {
                    flags = Some(f.split_whitespace().map(str::to_owned).collect::<Vec<_>>());
                }
            }
        }
        let flags = flags.expect("the array's mapping is in smaps");
        assert!(flags.iter().any(|f| f == "hg"), "VmFlags {flags:?}");
    }

    #[test]
    fn small_arrays_are_plain() {
        assert!(!advise([0u8; 16].as_ptr(), 16));
    }
}
