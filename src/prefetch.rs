//! A cache-line prefetch hint, the one place that issues `prefetcht0`: the traversal kernels
//! (`accel::traverse`) and the photon kd-tree's gather (`photon::kdtree`) call it.

/// Prefetches the cache line holding `p` into every cache level (any address: a hint that
/// never faults and changes no memory; nothing on targets other than x86-64).
#[inline(always)]
pub(crate) fn prefetch_line(p: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `_mm_prefetch` requires SSE, which every x86_64 target has. It is a hint: it
    // never faults and has no effect on memory, whatever the address.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(p.cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}
