//! Multiple importance sampling weights.

/// Power heuristic (β = 2) weight of a sample drawn with pdf `a` when the other strategy
/// would have drawn it with pdf `b` (one sample each). Infinite `a` (a delta strategy) gets 1.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 <= 0.0 || !(a2 + b2).is_finite() {
        return if a >= b { 1.0 } else { 0.0 };
    }
    a2 / (a2 + b2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_of_two_strategies_sum_to_one() {
        for (a, b) in [(1.0, 2.0), (0.3, 0.0), (1e-20, 1e-20), (5.0, 1e30)] {
            let s = power_heuristic(a, b) + power_heuristic(b, a);
            assert!((s - 1.0).abs() < 1e-6, "{a} {b}: {s}");
        }
        assert_eq!(power_heuristic(f32::INFINITY, 3.0), 1.0);
    }
}
