//! Where tolerances come from. Each function states its derivation; a case
//! never types a bare number as a tolerance without one of these or a
//! written reason.

/// Relative round-off floor for quantities accumulated over up to ~10⁴
/// steps: each step adds a few ulps (2.2e-16), so 1e-9 relative is five
/// orders of magnitude above the accumulated round-off and far below any
/// discretization error the harness looks at.
pub const ROUND_OFF_RELATIVE: f64 = 1e-9;

/// Safety factor on the step-doubling (Richardson) estimate: a chosen
/// margin, not a derived bound. What it covers: with the global error
/// e(h) = C hᵖ + D hᵖ⁺¹ + …, the estimate [`richardson_error`],
/// E = (y_h − y_{h/2})/(1 − 2⁻ᵖ), equals C hᵖ + D hᵖ⁺¹ (1 − 2⁻ᵖ⁻¹)/(1 − 2⁻ᵖ),
/// so e(h) − E = −D hᵖ⁺¹ / (2 (2ᵖ − 1)). With ρ = |D h / C| the size of
/// the next-order term against the leading one at this step,
/// |e| ≤ |E| (1 + ρ / (2 (2ᵖ − 1))) to first order: the factor 1.5 holds
/// while ρ ≤ 2ᵖ − 1 (1 for order 1, 3 for order 2, 15 for order 4).
/// ρ is not measured, so the rows built on it are `consistency` rows:
/// they show the error behaving as the method's order says; a method whose
/// real order is lower than claimed (error halving instead of dividing by
/// 2ᵖ) exceeds it.
pub const RICHARDSON_FACTOR: f64 = 1.5;

/// Richardson estimate of the global error of an order-`p` method at step h,
/// from its results at h and h/2: `e(h) ≈ (y_h − y_{h/2}) / (1 − 2^−p)`.
pub fn richardson_error(value_h: f64, value_half: f64, order: u32) -> f64 {
    (value_h - value_half) / (1.0 - 0.5f64.powi(order as i32))
}

/// The tolerance for a fixed-step method's value against an exact
/// reference: [`RICHARDSON_FACTOR`] times the step-doubling estimate of its
/// own error, but never below the round-off floor `floor`.
pub fn from_order(value_h: f64, value_half: f64, order: u32, floor: f64) -> f64 {
    (RICHARDSON_FACTOR * richardson_error(value_h, value_half, order).abs()).max(floor)
}

/// What [`RICHARDSON_FACTOR`] covers at order `order`: the largest ratio
/// of the next-order term to the leading one, 2ᵖ − 1.
pub fn richardson_cover(order: u32) -> u32 {
    (1u32 << order) - 1
}

/// The reason string that goes with [`from_order`].
pub fn from_order_reason(order: u32, floor: f64) -> String {
    format!(
        "{RICHARDSON_FACTOR} x step-doubling (Richardson) estimate of the order-{order} global error, floor {floor:e} (round-off); {RICHARDSON_FACTOR} is a chosen margin, covering a next-order term up to {} x the leading one (harness/src/tolerance.rs)",
        richardson_cover(order)
    )
}

/// Half a unit of the last digit of a value printed with `decimals`
/// decimals (the precision of a quoted reference number).
pub fn half_unit(decimals: i32) -> f64 {
    0.5 * 10f64.powi(-decimals)
}
