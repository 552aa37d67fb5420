//! The tests' random numbers: a xorshift64 stream of floats uniform in [−1, 1), the same
//! stream for the same seed, so every ray-layer test draws its soups and rays reproducibly.

/// Floats uniform in [−1, 1) (24 random bits each) from a xorshift64 generator seeded with
/// `seed` (non-zero).
pub(crate) fn signed_uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}
