//! A deterministic stream of numbers for the solver's unit tests (a
//! linear congruential generator: the tests need variety, not quality).

/// Numbers in [−1, 1), the same sequence for the same seed.
pub(crate) struct Numbers(pub u64);

impl Numbers {
    /// The next number, in [−1, 1).
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}
